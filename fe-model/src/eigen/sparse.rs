//! Sparse shift-invert Lanczos for the lowest modes of large models.
//!
//! With `A = K − σM = Pᵀ L Lᵀ P` (σ below the wanted spectrum, negative for free–free models
//! with rigid modes), the symmetric operator `T = L⁻¹ (P M Pᵀ) L⁻ᵀ` has eigenvalues
//! `θ = 1/(λ − σ)`: the lowest λ become the largest θ (Ericsson & Ruhe 1980, the ARPACK/eigsh
//! shift-invert mode 3 with a Cholesky-symmetrised operator), found here by a thick-restart
//! **block** Lanczos (module `block_lanczos`): the operator runs on blocks of
//! [`SparseEigenOptions::block_size`] vectors, where faer's supernodal triangular solves cost
//! a fraction per vector of single-vector solves (the single-vector Krylov–Schur of
//! `faer::matrix_free` spent 80 % of the 60 480-DOF tire's time in one-vector solves).
//! `φ = Pᵀ L⁻ᵀ y / √θ` is M-normalised (Ritz vectors of `T` are T-orthogonal, so the φ are
//! M-orthonormal to round-off).
//!
//! Threads: the numeric factorisations run on rayon's current pool (faer's `Par::rayon`); with
//! two or more threads the block solves split the block's columns into two halves solved
//! concurrently, the mass product `P M Pᵀ X` splits its rows, and the Sturm factorisation
//! runs beside the back-transform and the orthogonality and residual checks; the dense
//! kernels of the Lanczos stay sequential. Run inside `rayon::ThreadPool::install` to choose the count.
//! Factors with fewer than [`SparseEigenOptions::parallel_min_factor_nnz`] non-zeros keep only
//! the concurrent Sturm count (the threaded kernels did not pay below it on two cores).
//!
//! Safeguards (shared/notes/rust-ecosystem.md §1.3): `extra` modes beyond the requested count
//! so that a multiplet at the cut is not split; a deterministic pseudo-random start block;
//! M-orthogonality check (catches ghost duplicates); a Sturm count by LDLᵀ of `K − cM` proving
//! no mode below the cut was missed; retries with a larger basis; a wall-clock limit.

use super::block_lanczos::{BlockKsOptions, block_krylov_schur};
use super::dense::dense_modes;
use super::factor::{Analysis, Llt, shifted};
use super::operator::{PermutedSymmetric, ProductWork};
use super::{Modes, frequency_hz};
use crate::FeError;
use crate::sparse::{sparse_times_dense, triplets};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::SparseColMatRef;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use serde::Serialize;
use std::time::{Duration, Instant};

/// Options of [`sparse_modes`].
#[derive(Debug, Clone)]
pub struct SparseEigenOptions {
    /// Shift σ \[rad²/s²\]; `None` = automatic: 0 if `K` is positive definite, otherwise a small
    /// negative shift `−10⁻⁶·tr(K)/tr(M)` (free–free models).
    pub shift: Option<f64>,
    /// Extra modes computed beyond the requested count (multiplets at the cut).
    pub extra: usize,
    /// Krylov basis size before a thick restart; `None` = `max(4·nev, nev + 4·block)`
    /// (rounded up to a multiple of the block size). On the tire (50 modes, block 8, per-pair
    /// test) 4·nev needs one restart and 304 operator applications, 3·nev three restarts and
    /// 360 at 60k and 121k DOF (15–25 % more time), 2·nev five to seven restarts.
    pub max_dim: Option<usize>,
    /// Convergence tolerance: Ritz residual `‖T y − θ y‖ ≤ tolerance · θ_max` of the
    /// shift-invert operator T (`≤ tolerance · θ` per pair with [`Self::per_pair_test`]).
    pub tolerance: f64,
    /// ARPACK's convergence test (`dsconv`) for the `count` returned modes: each Ritz pair
    /// against its own value, `‖T y − θ y‖ ≤ tolerance · θ`, stricter than the default
    /// `tolerance · θ_max` for the smaller θ (the higher modes); the [`Self::extra`] pairs,
    /// which only place the Sturm cut, keep `tolerance · θ_max`. Default true: each returned
    /// mode meets the test that scipy's `eigsh` applies (with the extras held to it too, the
    /// 60 480-DOF tire needed 360 instead of 296 operator applications).
    pub per_pair_test: bool,
    /// Block width of the block Lanczos (right-hand sides per triangular solve). Default 8:
    /// the solves are bound by reading L, so a wider block costs little more per block, but
    /// the Krylov space grows less per vector and each vector must be orthogonalised against
    /// a larger basis (50 modes of the tire: 296 vectors at width 8, 276 at 4 at 60 480 DOF,
    /// 5.5 against 7.0 s; 672 at width 24 at 30 240 DOF, 4.0 against 2.9 s at width 8).
    pub block_size: usize,
    /// Maximum Krylov–Schur restarts per attempt.
    pub max_restarts: usize,
    /// Largest allowed |φᵢᵀ M φⱼ − δᵢⱼ|.
    pub orthogonality_tol: f64,
    /// Run the Sturm-sequence check.
    pub sturm_check: bool,
    /// Attempts (each with a 1.5× larger subspace) before giving up.
    pub attempts: usize,
    /// Wall-clock limit of one Lanczos run.
    pub timeout: Duration,
    /// Models with at most this many DOFs are solved densely.
    pub dense_below: usize,
    /// Fewest non-zeros of the Cholesky factor L for which the factorisations, the block solves
    /// and the sparse products use the threads of rayon's current pool; below it each runs on
    /// one thread, and only the Sturm count runs beside the back-transform and checks. Default
    /// 25 million: on the two-core test machine the threaded kernels cost more than they saved
    /// at nnz(L) = 8.7 M and 17.6 M (the generated tire at 30 240 and 60 480 DOF: 2.87 against
    /// 2.44 s and 5.53 against 5.11 s wall, BENCHMARKS "sparse eigen") and saved 27 % at 35.5 M
    /// (120 960 DOF: 9.31 against 12.82 s). The solves read L once per block, so below this size
    /// two threads compete for the memory bandwidth one of them already uses.
    pub parallel_min_factor_nnz: usize,
}

impl Default for SparseEigenOptions {
    fn default() -> Self {
        Self {
            shift: None,
            extra: 4,
            max_dim: None,
            tolerance: 1e-12,
            per_pair_test: true,
            block_size: 8,
            max_restarts: 500,
            orthogonality_tol: 1e-6,
            sturm_check: true,
            attempts: 3,
            timeout: Duration::from_secs(1800),
            dense_below: 400,
            parallel_min_factor_nnz: 25_000_000,
        }
    }
}

/// Diagnostics of a sparse eigen solution.
#[derive(Debug, Clone, Serialize)]
pub struct SparseEigenReport {
    /// DOFs.
    pub dof: usize,
    /// Shift σ used \[rad²/s²\].
    pub shift: f64,
    /// Krylov basis size of the accepted attempt.
    pub max_dim: usize,
    /// Block width of the block Lanczos.
    pub block_size: usize,
    /// Thick restarts of the accepted attempt.
    pub restarts: usize,
    /// Operator applications (vectors through `L⁻ᵀ`, M, `L⁻¹`), all attempts.
    pub operator_applications: usize,
    /// Attempts made.
    pub attempts: usize,
    /// Converged Ritz pairs of the accepted attempt.
    pub converged: usize,
    /// Non-zeros of the Cholesky factor.
    pub factor_nnz: usize,
    /// Largest |φᵢᵀ M φⱼ − δᵢⱼ|.
    pub max_orthogonality_error: f64,
    /// Largest relative residual ‖Kφ − λMφ‖ / ‖Kφ‖ (or ‖λMφ‖ when larger).
    pub max_relative_residual: f64,
    /// Sturm cut c \[rad²/s²\] (between the last returned mode and the next distinct one).
    pub sturm_cut: Option<f64>,
    /// Negative pivots of LDLᵀ of `K − cM` (eigenvalues below the cut).
    pub sturm_count: Option<usize>,
    /// Modes found below the cut (must equal `sturm_count`).
    pub found_below_cut: Option<usize>,
    /// Whether the model was small enough to be solved densely.
    pub dense_fallback: bool,
    /// Why earlier attempts were rejected (empty when the first attempt passed).
    pub rejected_attempts: Vec<String>,
    /// Wall-clock seconds: symbolic + numeric Cholesky of `K − σM`.
    pub seconds_factor: f64,
    /// Wall-clock seconds in the block Lanczos (all attempts).
    pub seconds_lanczos: f64,
    /// Of `seconds_lanczos`: in the operator (the two block triangular solves and the mass
    /// product); the rest is orthogonalisation, Rayleigh–Ritz and restarts.
    pub seconds_operator: f64,
    /// Wall-clock seconds of the Sturm-count LDLᵀ factorizations.
    pub seconds_sturm: f64,
}

/// Deterministic pseudo-random start block (a fixed linear congruential sequence; no
/// symmetry, so that modes of every symmetry class are reached).
fn start_block(n: usize, b: usize, seed: u64) -> Mat<f64> {
    let mut s = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut x = Mat::zeros(n, b);
    for j in 0..b {
        for i in 0..n {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            x[(i, j)] = ((s >> 11) as f64 / (1u64 << 53) as f64) - 0.5;
        }
    }
    x
}

/// The `count` lowest eigenpairs of `K φ = λ M φ` for sparse symmetric K (semi-definite allowed
/// with a negative shift) and symmetric positive definite M, with the safeguards of the module
/// documentation. Returns the modes (ascending, M-normalised, sign convention of [`Modes`]) and
/// a diagnostic report.
pub fn sparse_modes(
    k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, count: usize,
    opts: &SparseEigenOptions,
) -> Result<(Modes, SparseEigenReport), FeError> {
    let n = k.nrows();
    if k.ncols() != n || m.nrows() != n || m.ncols() != n {
        return Err(FeError::Dimension {
            context: "sparse_modes: K and M must be square and of equal size".into(),
            expected: n,
            got: m.nrows(),
        });
    }
    for (name, a) in [("K", k), ("M", m)] {
        if let Some((r, c, v)) = triplets(a).find(|t| !t.2.is_finite()) {
            return Err(FeError::Eigen(format!(
                "{name}[{r},{c}] = {v} is not finite"
            )));
        }
    }
    if count == 0 || n == 0 {
        return Err(FeError::param(
            "count",
            count as f64,
            "must be >= 1 and <= the number of DOFs",
        ));
    }
    let count = count.min(n);
    let nev = (count + opts.extra).min(n);
    let block = opts.block_size.max(1);
    let base_dim = opts
        .max_dim
        .unwrap_or((4 * nev).max(nev + 4 * block))
        .max(nev + 2 * block);

    if n <= opts.dense_below || n <= base_dim + 4 * block {
        let modes = dense_modes(k.to_dense().as_ref(), m.to_dense().as_ref(), count)?;
        let report = SparseEigenReport {
            dof: n,
            shift: 0.0,
            max_dim: n,
            block_size: 0,
            restarts: 0,
            operator_applications: 0,
            attempts: 1,
            converged: n,
            factor_nnz: 0,
            max_orthogonality_error: orthogonality_error(m, modes.vectors.as_ref()),
            max_relative_residual: max_residual(k, m, &modes),
            sturm_cut: None,
            sturm_count: None,
            found_below_cut: None,
            dense_fallback: true,
            rejected_attempts: Vec::new(),
            seconds_factor: 0.0,
            seconds_lanczos: 0.0,
            seconds_operator: 0.0,
            seconds_sturm: 0.0,
        };
        return Ok((modes, report));
    }

    // factorization of K − σM on the union pattern
    let t_factor = Instant::now();
    let a0 = shifted(k, m, 0.0)?;
    // the threads of the pool in the factorisations, solves and products only for a factor
    // large enough to pay for them; the Sturm count beside the back-transform at any size
    let analysis = Analysis::new(a0.as_ref())?;
    let threaded =
        rayon::current_num_threads() >= 2 && analysis.factor_nnz() >= opts.parallel_min_factor_nnz;
    let analysis = analysis.with_par(if threaded { Par::rayon(0) } else { Par::Seq });
    let (sigma, llt) = match opts.shift {
        Some(s) => {
            let a = shifted(k, m, s)?;
            (
                s,
                analysis.llt(a.as_ref(), &format!("K - sigma M (sigma = {s})"))?,
            )
        }
        None => match analysis.llt(a0.as_ref(), "K") {
            Ok(l) => (0.0, l),
            Err(_) => {
                let tr = |a: SparseColMatRef<'_, usize, f64>| {
                    triplets(a).filter(|t| t.0 == t.1).map(|t| t.2).sum::<f64>()
                };
                let s = -1e-6 * tr(k) / tr(m);
                let a = shifted(k, m, s)?;
                (
                    s,
                    analysis.llt(a.as_ref(), &format!("K - sigma M (sigma = {s:e})"))?,
                )
            }
        },
    };
    let seconds_factor = t_factor.elapsed().as_secs_f64();
    let (fwd, inv) = analysis.perm();
    let m_perm = PermutedSymmetric::new(m, &fwd, &inv)?;
    // the pool's threads (rayon::current_num_threads) in the block solves and dense kernels
    // dense kernels of the Lanczos sequential: on the skinny n × b blocks faer's parallel
    // matmul was slower on the two shared cores (measured 2.4-5.6 s against 2.1-2.7 s at
    // 30 240 DOF); the block solves and the mass product use the pool's threads themselves
    let par = Par::Seq;
    let mut dim = base_dim;
    let mut rejected = Vec::new();
    let (mut seconds_lanczos, mut seconds_sturm, mut seconds_operator) = (0.0, 0.0, 0.0);
    let mut applications = 0usize;
    let mut last_err = FeError::Eigen("no attempt made".into());
    let deadline = Instant::now() + opts.timeout;
    for attempt in 1..=opts.attempts.max(1) {
        let t_l = Instant::now();
        // shift-invert operator T x = L⁻¹ P M Pᵀ L⁻ᵀ x on a block, scratch allocated once
        let mut tmp = Mat::<f64>::zeros(n, block);
        let mut work = ProductWork::default();
        let mut apply = |mut out: MatMut<'_, f64>, x: MatRef<'_, f64>| {
            tmp.copy_from(x);
            split_solve(&llt, tmp.as_mut(), true, threaded);
            m_perm.apply(tmp.as_ref(), out.as_mut(), &mut work, threaded);
            split_solve(&llt, out, false, threaded);
        };
        let ks = block_krylov_schur(
            n,
            &mut apply,
            start_block(n, block, 12345 + attempt as u64).as_ref(),
            &BlockKsOptions {
                nev,
                block,
                max_dim: dim,
                tol: opts.tolerance,
                per_pair: if opts.per_pair_test { count } else { 0 },
                max_restarts: opts.max_restarts,
                deadline,
                par,
            },
        )?;
        seconds_lanczos += t_l.elapsed().as_secs_f64();
        seconds_operator += ks.seconds_apply;
        applications += ks.applies;
        let (vals, vecs, restarts) = (ks.values, ks.vectors, ks.restarts);
        let conv = vals.len();
        let result = (|| -> Result<(Modes, SparseEigenReport), FeError> {
            if conv < count {
                return Err(FeError::Eigen(format!(
                    "only {conv} of {nev} Ritz pairs converged (subspace {dim})"
                )));
            }
            for &theta in &vals {
                if theta.is_nan() || theta <= 0.0 {
                    return Err(FeError::Eigen(format!(
                        "non-positive Ritz value {theta:e}: shift σ = {sigma:e} is not below the spectrum"
                    )));
                }
            }
            // λ = σ + 1/θ, ascending as the modes will be sorted
            let lambdas: Vec<f64> = vals.iter().map(|&theta| sigma + 1.0 / theta).collect();
            let mut lam = lambdas.clone();
            lam.sort_by(f64::total_cmp);
            // the Sturm count at the cut between the last returned mode and the next distinct
            // converged one: (cut, modes found below it, negative pivots, seconds)
            let sturm_job = || -> Result<Option<(f64, usize, usize, f64)>, FeError> {
                if !opts.sturm_check {
                    return Ok(None);
                }
                let last = lam[count - 1];
                let tolgap = 1e-7 * last.abs().max(sigma.abs()).max(1e-300);
                let next = lam[count..].iter().copied().find(|&l| l - last > tolgap);
                let c = match next {
                    Some(nx) => 0.5 * (last + nx),
                    None => last + 1e-4 * last.abs().max(1e-12),
                };
                let below = lam.iter().filter(|&&l| l < c).count();
                let t_s = Instant::now();
                let a = shifted(k, m, c)?;
                let negs = analysis.negative_pivots(a.as_ref())?;
                Ok(Some((c, below, negs, t_s.elapsed().as_secs_f64())))
            };
            // back-transform φ = Pᵀ L⁻ᵀ y / √θ, M-orthogonality and residuals
            let modes_job = || -> Result<(Modes, f64, f64), FeError> {
                let mut y = vecs;
                split_solve(&llt, y.as_mut(), true, threaded);
                // y ← L⁻ᵀ y / √θ = P φ: the modes in the factor's order, where the checks
                // run on the gather products of P K Pᵀ and P M Pᵀ (norms and the Gram matrix
                // do not depend on the order of the rows)
                for (j, &theta) in vals.iter().enumerate() {
                    let s = 1.0 / theta.sqrt();
                    y.as_mut().col_mut(j).iter_mut().for_each(|x| *x *= s);
                }
                let mut order: Vec<usize> = (0..conv).collect();
                order.sort_by(|&a, &b| lambdas[a].total_cmp(&lambdas[b]));
                let kept = &order[..count];
                let k_perm = PermutedSymmetric::new(k, &fwd, &inv)?;
                let (orth, resid) =
                    permuted_checks(&k_perm, &m_perm, &lambdas, y.as_ref(), kept, threaded);
                let mut phi = Mat::from_fn(n, count, |r, j| y[(inv[r], kept[j])]);
                super::normalize_signs(phi.as_mut());
                let values: Vec<f64> = kept.iter().map(|&i| lambdas[i]).collect();
                let modes = Modes {
                    frequencies_hz: values.iter().map(|&l| frequency_hz(l)).collect(),
                    values,
                    vectors: phi,
                };
                Ok((modes, orth, resid))
            };
            // with two threads the Sturm factorisation runs beside the back-transform and checks
            let (sturm_res, modes_res) = if rayon::current_num_threads() >= 2 {
                rayon::join(sturm_job, modes_job)
            } else {
                (sturm_job(), modes_job())
            };
            let (modes, orth, resid) = modes_res?;
            if orth > opts.orthogonality_tol {
                return Err(FeError::Eigen(format!(
                    "M-orthogonality check failed (max |φᵢᵀMφⱼ − δᵢⱼ| = {orth:e}): duplicated (ghost) Ritz vector"
                )));
            }
            let (mut cut, mut found_below, mut sturm) = (None, None, None);
            if let Some((c, below, negs, secs)) = sturm_res? {
                seconds_sturm += secs;
                if negs != below {
                    return Err(FeError::Eigen(format!(
                        "Sturm check failed: {negs} eigenvalues below {c:e} rad²/s² ({:.6} Hz) but {below} found",
                        frequency_hz(c)
                    )));
                }
                cut = Some(c);
                found_below = Some(below);
                sturm = Some(negs);
            }
            let report = SparseEigenReport {
                dof: n,
                shift: sigma,
                max_dim: dim,
                block_size: block,
                restarts,
                operator_applications: applications,
                attempts: attempt,
                converged: conv,
                factor_nnz: analysis.factor_nnz(),
                max_orthogonality_error: orth,
                max_relative_residual: resid,
                sturm_cut: cut,
                sturm_count: sturm,
                found_below_cut: found_below,
                dense_fallback: false,
                rejected_attempts: rejected.clone(),
                seconds_factor,
                seconds_lanczos,
                seconds_operator,
                seconds_sturm,
            };
            Ok((modes, report))
        })();
        match result {
            Ok(r) => return Ok(r),
            Err(e) => {
                rejected.push(format!("attempt {attempt} (subspace {dim}): {e}"));
                last_err = e;
                dim = ((dim * 3) / 2).min(n.saturating_sub(2 * block));
            }
        }
    }
    Err(last_err)
}

/// The checks of [`orthogonality_error`] and [`max_residual`] on modes given in the factor's
/// order, `Y = P Φ` (columns M-normalised, `lambdas[j]` the eigenvalue of column j): the
/// largest `|Yᵀ (P M Pᵀ) Y − I|` over all columns, and the largest relative residual
/// `‖(P K Pᵀ) y − λ (P M Pᵀ) y‖ / max(‖P K Pᵀ y‖, ‖λ P M Pᵀ y‖)` over the columns `kept`. Equal
/// to the unpermuted checks up to round-off (a permutation changes neither inner products nor
/// norms), with the mass product formed once for both and the gather kernels of the operator
/// (no stored zeros, rows split over rayon's pool).
fn permuted_checks(
    k_perm: &PermutedSymmetric, m_perm: &PermutedSymmetric, lambdas: &[f64], y: MatRef<'_, f64>,
    kept: &[usize], threaded: bool,
) -> (f64, f64) {
    let (n, c) = (y.nrows(), y.ncols());
    let mut work = ProductWork::default();
    let mut my = Mat::<f64>::zeros(n, c);
    m_perm.apply(y, my.as_mut(), &mut work, threaded);
    let orth = gram_deviation(y, my.as_ref());
    let ysel = Mat::from_fn(n, kept.len(), |r, j| y[(r, kept[j])]);
    let mut ky = Mat::<f64>::zeros(n, kept.len());
    k_perm.apply(ysel.as_ref(), ky.as_mut(), &mut work, threaded);
    let worst = relative_residual(ky.as_ref(), |j| (lambdas[kept[j]], my.col(kept[j])));
    (orth, worst)
}

/// `max |Xᵀ (M X) − I|` from `X` and the product `M X`.
fn gram_deviation(x: MatRef<'_, f64>, mx: MatRef<'_, f64>) -> f64 {
    let c = x.ncols();
    let mut g = Mat::<f64>::zeros(c, c);
    faer::linalg::matmul::matmul(g.as_mut(), Accum::Replace, x.transpose(), mx, 1.0, Par::Seq);
    let mut e: f64 = 0.0;
    for i in 0..c {
        for j in 0..c {
            let d = if i == j { 1.0 } else { 0.0 };
            e = e.max((g[(i, j)] - d).abs());
        }
    }
    e
}

/// Largest `‖K φ_j − λ_j M φ_j‖ / max(‖K φ_j‖, ‖λ_j M φ_j‖)` over the columns `j` of `kx`
/// (`K φ_j`), with `pair(j)` giving `λ_j` and the column `M φ_j`.
fn relative_residual<'a>(
    kx: MatRef<'_, f64>, pair: impl Fn(usize) -> (f64, faer::ColRef<'a, f64>),
) -> f64 {
    let mut worst: f64 = 0.0;
    for j in 0..kx.ncols() {
        let (l, mc) = pair(j);
        let kc = kx.col(j);
        let (mut r, mut a, mut b) = (0.0, 0.0, 0.0);
        for i in 0..kx.nrows() {
            let (k, m) = (kc[i], l * mc[i]);
            r += (k - m) * (k - m);
            a += k * k;
            b += m * m;
        }
        let den = a.max(b).sqrt();
        if den > 0.0 {
            worst = worst.max(r.sqrt() / den);
        }
    }
    worst
}

/// `x ← L⁻ᵀ x` (`transpose`) or `x ← L⁻¹ x` on a block: with two or more threads in rayon's
/// current pool the columns are split into two halves solved concurrently, each by the
/// sequential supernodal kernel (the solves are bound by reading L; faer's parallel solve
/// splits the supernodal tree instead, whose small supernodes near the leaves make it slower
/// than the sequential kernel on this model).
fn split_solve(llt: &Llt, x: MatMut<'_, f64>, transpose: bool, threaded: bool) {
    let one = |x: MatMut<'_, f64>| {
        let mut mem = MemBuffer::new(llt.scratch(x.ncols(), Par::Seq));
        let stack = MemStack::new(&mut mem);
        if transpose {
            llt.lt_solve(x, Par::Seq, stack);
        } else {
            llt.l_solve(x, Par::Seq, stack);
        }
    };
    if threaded && x.ncols() >= 2 {
        let h = x.ncols() / 2;
        let (a, b) = x.split_at_col_mut(h);
        rayon::join(|| one(a), || one(b));
    } else {
        one(x);
    }
}

/// `max |φᵢᵀ M φⱼ − δᵢⱼ|`.
pub fn orthogonality_error(m: SparseColMatRef<'_, usize, f64>, phi: MatRef<'_, f64>) -> f64 {
    gram_deviation(phi, sparse_times_dense(m, phi).as_ref())
}

/// Largest relative residual `‖Kφ − λMφ‖ / max(‖Kφ‖, ‖λMφ‖)` over the modes.
pub fn max_residual(
    k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, modes: &Modes,
) -> f64 {
    let phi = modes.vectors.as_ref();
    let kp = sparse_times_dense(k, phi);
    let mp = sparse_times_dense(m, phi);
    relative_residual(kp.as_ref(), |j| (modes.values[j], mp.col(j)))
}
