//! Physical plausibility of a stiffness and mass pair read from files, before an eigen solve or
//! a reduction: the checks that turn silent nonsense (an all-zero K giving −7.5·10⁻¹⁵⁹ Hz, an
//! indefinite K giving 0 Hz) into errors naming the offending DOFs.
//!
//! For `K φ = λ M φ` to describe free vibration, M must be symmetric positive definite (every
//! DOF carries mass) and K symmetric positive semi-definite (rigid-body motions allowed, no
//! negative stiffness): Géradin & Rixen, *Mechanical Vibrations* §2.3. The checks, cheapest
//! first:
//!
//! 1. both matrices square, of equal size, with finite entries;
//! 2. `M_ii > 0` for every DOF (a zero diagonal is a massless DOF: an error, or a warning when
//!    [`PairCheckOptions::massless_dofs_allowed`], as static condensation handles them);
//!    then a sparse Cholesky of M when no DOF is massless (the first non-positive pivot is
//!    reported by DOF);
//! 3. K not all zero; `K_ii ≥ 0`, and `K_ii > 0` wherever the row has off-diagonal entries
//!    (otherwise a 2×2 principal minor is negative); rows of K that are entirely zero are a
//!    warning (a DOF without stiffness moves freely at 0 Hz);
//! 4. the inertia of `K − σ M` with `σ = −10⁻⁶·tr K / tr M` (Sylvester's law of inertia, as in
//!    the Sturm check of [`crate::eigen`]): a negative pivot means an eigenvalue below σ, i.e.
//!    K is indefinite; the DOFs of the negative pivots are reported.

use crate::FeError;
use crate::eigen::factor::{Analysis, shifted};
use crate::sparse::triplets;
use faer::sparse::SparseColMatRef;

/// What the checks tolerate.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PairCheckOptions {
    /// Massless DOFs (`M_ii = 0`) are a warning instead of an error (a Guyan or
    /// Craig–Bampton reduction condenses them; an eigen solve needs M positive definite).
    pub massless_dofs_allowed: bool,
}

/// DOFs listed in messages: 1-based (the row numbers of a Matrix Market file), at most 8.
fn dof_list(dofs: &[usize]) -> String {
    let mut s: Vec<String> = dofs.iter().take(8).map(|d| (d + 1).to_string()).collect();
    if dofs.len() > 8 {
        s.push(format!("… ({} in all)", dofs.len()));
    }
    s.join(", ")
}

fn implausible(matrix: &str, reason: String) -> FeError {
    FeError::Implausible {
        matrix: matrix.to_string(),
        reason,
    }
}

/// The error "`what` at DOFs …" of `matrix` when `bad` holds for some of its `n` DOFs.
fn refuse_dofs(
    matrix: &str, n: usize, bad: impl Fn(usize) -> bool, what: &str,
) -> Result<(), FeError> {
    let dofs: Vec<usize> = (0..n).filter(|&i| bad(i)).collect();
    if dofs.is_empty() {
        return Ok(());
    }
    Err(implausible(
        matrix,
        format!("{what} at DOFs {}", dof_list(&dofs)),
    ))
}

/// Relative tolerance of [`check_symmetric`]: `|a_ij − a_ji| ≤ 10⁻⁸ max|A|` (the
/// rounding of an exported matrix, far below any physical asymmetry).
pub const SYMMETRY_TOL: f64 = 1e-8;

/// `Ok` when `a` (named `matrix` in the error) is symmetric to [`SYMMETRY_TOL`]; otherwise
/// [`FeError::Implausible`] naming the first pair of mirrored entries that differ (1-based).
/// A stiffness or mass matrix is symmetric (Maxwell–Betti reciprocity; Géradin & Rixen §2.3);
/// a reduction of a non-symmetric one is silently wrong (issue 35).
pub fn check_symmetric(matrix: &str, a: SparseColMatRef<'_, usize, f64>) -> Result<(), FeError> {
    use std::collections::HashMap;
    let mut entries: HashMap<(usize, usize), f64> = HashMap::new();
    let mut max = 0.0f64;
    for (r, c, v) in triplets(a) {
        *entries.entry((r, c)).or_insert(0.0) += v;
        max = max.max(v.abs());
    }
    let tol = SYMMETRY_TOL * max;
    let mut worst: Option<(usize, usize, f64, f64)> = None;
    for (&(r, c), &v) in &entries {
        if r < c {
            continue;
        }
        let w = entries.get(&(c, r)).copied().unwrap_or(0.0);
        if (v - w).abs() > tol && worst.is_none_or(|x| (v - w).abs() > (x.2 - x.3).abs()) {
            worst = Some((r, c, v, w));
        }
    }
    for (&(r, c), &v) in &entries {
        if r < c && !entries.contains_key(&(c, r)) && v.abs() > tol && worst.is_none() {
            worst = Some((r, c, v, 0.0));
        }
    }
    match worst {
        None => Ok(()),
        Some((r, c, v, w)) => Err(implausible(
            matrix,
            format!(
                "not symmetric: entry ({}, {}) = {v:e} but ({}, {}) = {w:e}",
                r + 1,
                c + 1,
                c + 1,
                r + 1
            ),
        )),
    }
}

/// Check K and M (module documentation); returns warnings (one line each) or the first error
/// as [`FeError::Implausible`] naming the matrix and the DOFs (1-based rows).
pub fn check_stiffness_mass(
    k: SparseColMatRef<'_, usize, f64>, m: SparseColMatRef<'_, usize, f64>, opts: &PairCheckOptions,
) -> Result<Vec<String>, FeError> {
    let n = k.nrows();
    if k.ncols() != n || m.nrows() != n || m.ncols() != n {
        return Err(FeError::Dimension {
            context: "K and M must be square and of equal size".into(),
            expected: n,
            got: m.nrows(),
        });
    }
    let mut warnings = Vec::new();
    let mut diag_k = vec![0.0; n];
    let mut diag_m = vec![0.0; n];
    let mut row_k = vec![false; n];
    let mut offdiag_k = vec![false; n];
    for (name, a, diag) in [("K", k, &mut diag_k), ("M", m, &mut diag_m)] {
        for (r, c, v) in triplets(a) {
            if !v.is_finite() {
                return Err(implausible(
                    name,
                    format!("entry ({}, {}) = {v} is not finite", r + 1, c + 1),
                ));
            }
            if r == c {
                diag[r] += v;
            }
        }
    }
    for (r, c, v) in triplets(k) {
        if v != 0.0 {
            row_k[r] = true;
            if r != c {
                offdiag_k[r] = true;
            }
        }
    }
    // M
    refuse_dofs(
        "M",
        n,
        |i| diag_m[i] < 0.0,
        "negative diagonal (negative mass)",
    )?;
    let massless: Vec<usize> = (0..n).filter(|&i| diag_m[i] == 0.0).collect();
    if massless.len() == n && n > 0 {
        return Err(implausible("M", "every diagonal entry is zero".into()));
    }
    if !massless.is_empty() {
        let msg = format!("zero diagonal (no mass) at DOFs {}", dof_list(&massless));
        if opts.massless_dofs_allowed {
            warnings.push(format!("matrix `M`: {msg}"));
        } else {
            return Err(implausible(
                "M",
                format!("{msg}: M must be positive definite"),
            ));
        }
    } else if n > 0 {
        let an = Analysis::new(m)?;
        an.llt(m, "M")?;
    }
    // K
    if !row_k.iter().any(|&x| x) {
        return Err(implausible(
            "K",
            "every entry is zero: no stiffness at all".into(),
        ));
    }
    refuse_dofs(
        "K",
        n,
        |i| diag_k[i] < 0.0,
        "negative diagonal (K is indefinite)",
    )?;
    refuse_dofs(
        "K",
        n,
        |i| diag_k[i] == 0.0 && offdiag_k[i],
        "zero diagonal with off-diagonal entries (K is indefinite)",
    )?;
    let free: Vec<usize> = (0..n).filter(|&i| !row_k[i]).collect();
    if !free.is_empty() {
        warnings.push(format!(
            "matrix `K`: no stiffness at DOFs {} (they move freely, at 0 Hz)",
            dof_list(&free)
        ));
    }
    // inertia of K − σM just below zero
    let (tr_k, tr_m) = (diag_k.iter().sum::<f64>(), diag_m.iter().sum::<f64>());
    let sigma = -1e-6 * tr_k / tr_m;
    let a = shifted(k, m, sigma)?;
    let an = Analysis::new(a.as_ref())?;
    match an.negative_pivot_dofs(a.as_ref()) {
        Ok(neg) if !neg.is_empty() => {
            return Err(implausible(
                "K",
                format!(
                    "indefinite: {} eigenvalue(s) of K φ = λ M φ below σ = {sigma:.3e} \
                     (negative pivots of K − σM at DOFs {})",
                    neg.len(),
                    dof_list(&neg)
                ),
            ));
        }
        Ok(_) => {}
        Err(e) => warnings.push(format!("matrix `K`: inertia check skipped ({e})")),
    }
    Ok(warnings)
}
