//! Polynomial least-squares mode-shape derivatives (Ribaric App. A.3, (A.5)–(A.11)).
//!
//! The polynomial space is that of the Vandermonde matrix (A.5) of degree `m`; the basis is
//! Legendre polynomials of the coordinate scaled to `[−1, 1]` (same space, far better conditioned
//! than raw monomials; the notes' \[choice\] of scaling). Known zero end values of an open grid are
//! included as collocation points (boundary-aware). `m + 1 = n` collocates (A.8), `m + 1 < n` is
//! the least-squares fit (A.9).

use crate::error::FlowError;
use crate::grid::{End, FlowGrid, Topology};
use faer::Mat;
use faer::linalg::solvers::SolveLstsq;

/// Legendre values, first and second derivatives (w.r.t. ξ) of degrees `0..=m` at `xi`.
fn legendre(m: usize, xi: f64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut p = vec![0.0; m + 1];
    let mut d = vec![0.0; m + 1];
    let mut dd = vec![0.0; m + 1];
    p[0] = 1.0;
    if m >= 1 {
        p[1] = xi;
        d[1] = 1.0;
    }
    for k in 1..m {
        let kf = k as f64;
        p[k + 1] = ((2.0 * kf + 1.0) * xi * p[k] - kf * p[k - 1]) / (kf + 1.0);
        // P'_{k+1} = P'_{k-1} + (2k+1) P_k, and its derivative.
        d[k + 1] = d[k - 1] + (2.0 * kf + 1.0) * p[k];
        dd[k + 1] = dd[k - 1] + (2.0 * kf + 1.0) * d[k];
    }
    (p, d, dd)
}

/// Dense `(D₁, D₂)` of the degree-`degree` least-squares fit on an open grid: `Ψ_,x = V_,x P`,
/// `P = V⁺ Ψ` (A.9)–(A.11).
pub fn polynomial_matrices(
    grid: &FlowGrid, degree: usize,
) -> Result<(Mat<f64>, Mat<f64>), FlowError> {
    let Topology::Open { start, end } = grid.topology() else {
        return Err(FlowError::MethodNotApplicable {
            method: "polynomial least squares",
            reason: "a closed (periodic) grid has no polynomial representation; use finite differences or FFT".into(),
        });
    };
    let n = grid.len();
    let mut pts: Vec<(Option<usize>, f64)> = Vec::with_capacity(n + 2);
    if let End::Zero(a) = start {
        pts.push((None, a));
    }
    pts.extend(
        grid.positions()
            .iter()
            .enumerate()
            .map(|(j, s)| (Some(j), *s)),
    );
    if let End::Zero(b) = end {
        pts.push((None, b));
    }
    let nc = pts.len();
    if degree + 1 > nc {
        return Err(FlowError::MethodNotApplicable {
            method: "polynomial least squares",
            reason: format!(
                "degree {degree} needs at least {} collocation points, the grid has {nc}",
                degree + 1
            ),
        });
    }
    let lo = pts[0].1;
    let hi = pts[nc - 1].1;
    let scale = 2.0 / (hi - lo);
    let xi = |s: f64| (2.0 * s - (lo + hi)) / (hi - lo);
    let mut v = Mat::<f64>::zeros(nc, degree + 1);
    for (r, p) in pts.iter().enumerate() {
        let (val, _, _) = legendre(degree, xi(p.1));
        for c in 0..=degree {
            v[(r, c)] = val[c];
        }
    }
    // Data-to-coefficient map restricted to the node columns (zero end values contribute nothing).
    let mut rhs = Mat::<f64>::zeros(nc, n);
    for (r, p) in pts.iter().enumerate() {
        if let Some(j) = p.0 {
            rhs[(r, j)] = 1.0;
        }
    }
    let qr = v.qr();
    let coef = qr.solve_lstsq(&rhs); // (degree+1) × n
    let mut vx = Mat::<f64>::zeros(n, degree + 1);
    let mut vxx = Mat::<f64>::zeros(n, degree + 1);
    for (j, s) in grid.positions().iter().enumerate() {
        let (_, d, dd) = legendre(degree, xi(*s));
        for c in 0..=degree {
            vx[(j, c)] = d[c] * scale;
            vxx[(j, c)] = dd[c] * scale * scale;
        }
    }
    Ok((&vx * &coef, &vxx * &coef))
}
