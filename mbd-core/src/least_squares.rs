//! Nonlinear least squares: the Levenberg–Marquardt method for `min ½‖r(p)‖²` over a few
//! parameters (curve fits: the tire's Magic Formula coefficients, `tire::magic_formula`).
//!
//! The step solves `(JᵀJ + λ D) δ = −Jᵀr` with Marquardt's scaling `D = diag(JᵀJ)` (kept at its
//! running maximum, so that a parameter whose column vanishes for a while keeps its damping)
//! by faer's Cholesky factorisation; the gain ratio `ρ` of the actual to the predicted decrease
//! `½ δᵀ(λ D δ − Jᵀr)` accepts or rejects it and updates the damping as Nielsen does
//! (Madsen, Nielsen & Tingleff, *Methods for non-linear least squares problems*, 2004,
//! Algorithm 3.16: `λ ← λ max(1/3, 1 − (2ρ − 1)³)` on success, `λ ← ν λ, ν ← 2ν` on failure).
//! The problems here are small (tens of residuals, up to a dozen parameters), so the normal
//! equations are formed densely. The `levenberg-marquardt` crate does the same on nalgebra
//! 0.34, a second nalgebra besides the workspace's: this module keeps the one matrix type.

use crate::MbdError;
use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

/// A least-squares problem `min ½ Σ r_i(p)²`.
pub trait LeastSquares {
    /// Number of residuals `m` (at least the number of parameters).
    fn residual_count(&self) -> usize;

    /// The residuals `r(p)` into `r` (length [`Self::residual_count`]). A non-finite value
    /// marks `p` as outside the model's domain: the step is rejected.
    fn residuals(&self, p: &[f64], r: &mut [f64]);

    /// The Jacobian `∂r_i/∂p_j` into `j` (`m × n`). Default: central differences with the step
    /// `1e-6 max(|p_j|, 1e-3)`.
    fn jacobian(&self, p: &[f64], j: &mut Mat<f64>) {
        let m = self.residual_count();
        let (mut rp, mut rm) = (vec![0.0; m], vec![0.0; m]);
        let mut q = p.to_vec();
        for k in 0..p.len() {
            let h = 1e-6 * p[k].abs().max(1e-3);
            q[k] = p[k] + h;
            self.residuals(&q, &mut rp);
            q[k] = p[k] - h;
            self.residuals(&q, &mut rm);
            q[k] = p[k];
            for i in 0..m {
                j[(i, k)] = (rp[i] - rm[i]) / (2.0 * h);
            }
        }
    }
}

/// When [`levenberg_marquardt`] stops.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmSettings {
    /// Most Jacobian evaluations (accepted or rejected steps count alike).
    pub max_iterations: usize,
    /// Gradient test: `‖Jᵀr‖∞ ≤ gtol` \[unit of `r`² per unit of `p`\].
    pub gtol: f64,
    /// Step test: `‖δ‖ ≤ xtol (‖p‖ + xtol)` \[-\].
    pub xtol: f64,
    /// Cost test: a successful step lowering `½‖r‖²` by at most `ftol` of it \[-\].
    pub ftol: f64,
}

impl Default for LmSettings {
    /// 400 iterations, `gtol = 0`, `xtol = ftol = 1e-14`: converge to round-off.
    fn default() -> Self {
        Self {
            max_iterations: 400,
            gtol: 0.0,
            xtol: 1e-14,
            ftol: 1e-14,
        }
    }
}

/// Why [`levenberg_marquardt`] stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LmStop {
    /// The gradient test held.
    Gradient,
    /// The step test held.
    Step,
    /// The cost test held.
    Cost,
    /// The cost is zero (an exact fit).
    ZeroCost,
    /// `max_iterations` reached (the best point so far is returned).
    Iterations,
}

/// The result of [`levenberg_marquardt`].
#[derive(Debug, Clone, PartialEq)]
pub struct LmResult {
    /// The parameters.
    pub p: Vec<f64>,
    /// `½‖r(p)‖²` there.
    pub cost: f64,
    /// Jacobian evaluations.
    pub iterations: usize,
    /// Why it stopped.
    pub stop: LmStop,
}

/// Minimise `½‖r(p)‖²` from `p0` by Levenberg–Marquardt (module documentation).
///
/// # Errors
/// [`MbdError::InvalidInput`] for fewer residuals than parameters or no parameters;
/// [`MbdError::NonFinite`] when `r(p0)` or the Jacobian is not finite.
pub fn levenberg_marquardt(
    problem: &impl LeastSquares, p0: &[f64], settings: &LmSettings,
) -> Result<LmResult, MbdError> {
    let n = p0.len();
    let m = problem.residual_count();
    if n == 0 || m < n {
        return Err(MbdError::InvalidInput {
            item: "least squares".into(),
            reason: format!(
                "{m} residuals for {n} parameters (need at least one residual per parameter, and one parameter)"
            ),
        });
    }
    let non_finite = |what: &str| MbdError::NonFinite {
        what: format!("least squares: {what}"),
        t: 0.0,
    };
    let mut p = p0.to_vec();
    let mut r = vec![0.0; m];
    problem.residuals(&p, &mut r);
    let mut cost = half_norm2(&r);
    if !cost.is_finite() {
        return Err(non_finite("residuals at the starting point"));
    }
    let mut jac = Mat::<f64>::zeros(m, n);
    let mut a = Mat::<f64>::zeros(n, n);
    let mut g = vec![0.0; n];
    let mut d = vec![0.0f64; n];
    let mut lambda = -1.0;
    let mut nu = 2.0;
    let mut fresh = true;
    let mut r_new = vec![0.0; m];
    let mut iterations = 0;
    let done = |p: Vec<f64>, cost, iterations, stop| {
        Ok(LmResult {
            p,
            cost,
            iterations,
            stop,
        })
    };
    while iterations < settings.max_iterations {
        if cost == 0.0 {
            return done(p, cost, iterations, LmStop::ZeroCost);
        }
        if fresh {
            iterations += 1;
            problem.jacobian(&p, &mut jac);
            if !jac.as_ref().is_all_finite() {
                return Err(non_finite("Jacobian"));
            }
            for i in 0..n {
                g[i] = (0..m).map(|k| jac[(k, i)] * r[k]).sum();
                for j in 0..=i {
                    let v: f64 = (0..m).map(|k| jac[(k, i)] * jac[(k, j)]).sum();
                    a[(i, j)] = v;
                    a[(j, i)] = v;
                }
                d[i] = d[i].max(a[(i, i)]);
            }
            if g.iter().fold(0.0f64, |s, v| s.max(v.abs())) <= settings.gtol {
                return done(p, cost, iterations, LmStop::Gradient);
            }
            if lambda < 0.0 {
                // Madsen et al. (3.14): λ₀ = τ max(JᵀJ)_ii with τ = 1e-3
                lambda = 1e-3 * d.iter().fold(0.0f64, |s, v| s.max(*v));
            }
            fresh = false;
        } else {
            // a rejected step counts as an iteration too (no fresh Jacobian)
            iterations += 1;
        }
        let floor = 1e-300_f64.max(f64::EPSILON * d.iter().fold(0.0f64, |s, v| s.max(*v)));
        let mut lhs = a.clone();
        for i in 0..n {
            lhs[(i, i)] += lambda * d[i].max(floor);
        }
        let Ok(llt) = lhs.llt(Side::Lower) else {
            lambda *= nu;
            nu *= 2.0;
            continue;
        };
        let rhs = Mat::<f64>::from_fn(n, 1, |i, _| -g[i]);
        let delta = llt.solve(&rhs);
        let step: Vec<f64> = (0..n).map(|i| delta[(i, 0)]).collect();
        let p_norm = p.iter().map(|v| v * v).sum::<f64>().sqrt();
        let step_norm = step.iter().map(|v| v * v).sum::<f64>().sqrt();
        if step_norm <= settings.xtol * (p_norm + settings.xtol) {
            return done(p, cost, iterations, LmStop::Step);
        }
        let p_new: Vec<f64> = p.iter().zip(&step).map(|(a, b)| a + b).collect();
        problem.residuals(&p_new, &mut r_new);
        let cost_new = half_norm2(&r_new);
        // predicted decrease ½ δᵀ(λ D δ − g) (Madsen et al. (3.11))
        let predicted: f64 = 0.5
            * (0..n)
                .map(|i| step[i] * (lambda * d[i].max(floor) * step[i] - g[i]))
                .sum::<f64>();
        // actual decrease ½(‖r‖² − ‖r_new‖²) as ½ Σ (r − r_new)(r + r_new): no cancellation of
        // two nearly equal costs near a minimum with a residual (the gain ratio stays exact
        // down to the round-off of the residuals themselves)
        let decrease: f64 = 0.5
            * r.iter()
                .zip(&r_new)
                .map(|(a, b)| (a - b) * (a + b))
                .sum::<f64>();
        let rho = if cost_new.is_finite() && predicted > 0.0 {
            decrease / predicted
        } else {
            -1.0
        };
        // a predicted decrease within the round-off of the cost cannot be confirmed by
        // evaluating it (near a minimum with a residual the cost changes only in its last
        // bits, and the residuals carry the round-off of the data they are computed from):
        // below 1e-12 of the cost the step of the local quadratic model is taken, and the fit
        // is done (the parameters then converge like Gauss–Newton's last step, not to √ε)
        let noise = 1e-12 * cost;
        let unresolvable = cost_new.is_finite() && predicted <= noise && decrease >= -noise;
        if rho > 0.0 || unresolvable {
            p = p_new;
            std::mem::swap(&mut r, &mut r_new);
            cost = cost_new;
            if unresolvable {
                return done(p, cost, iterations, LmStop::Cost);
            }
            lambda *= (1.0f64 / 3.0).max(1.0 - (2.0 * rho - 1.0).powi(3));
            nu = 2.0;
            fresh = true;
            if decrease <= settings.ftol * (cost + decrease) {
                return done(p, cost, iterations, LmStop::Cost);
            }
        } else {
            lambda *= nu;
            nu *= 2.0;
        }
    }
    done(p, cost, iterations, LmStop::Iterations)
}

fn half_norm2(r: &[f64]) -> f64 {
    0.5 * r.iter().map(|v| v * v).sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock as least squares: r = (10 (p₂ − p₁²), 1 − p₁), minimum 0 at (1, 1).
    struct Rosenbrock;
    impl LeastSquares for Rosenbrock {
        fn residual_count(&self) -> usize {
            2
        }
        fn residuals(&self, p: &[f64], r: &mut [f64]) {
            r[0] = 10.0 * (p[1] - p[0] * p[0]);
            r[1] = 1.0 - p[0];
        }
    }

    // Madsen, Nielsen & Tingleff Example 3.13 / Moré, Garbow & Hillstrom problem 1: from
    // (−1.2, 1) to the minimum (1, 1).
    #[test]
    fn rosenbrock_reaches_its_minimum() {
        let s = levenberg_marquardt(&Rosenbrock, &[-1.2, 1.0], &LmSettings::default()).unwrap();
        assert!(
            (s.p[0] - 1.0).abs() < 1e-10 && (s.p[1] - 1.0).abs() < 1e-10,
            "{s:?}"
        );
        assert!(s.cost < 1e-20, "{s:?}");
    }

    /// y = a e^{b x} + c sampled without noise: the fit returns (a, b, c).
    struct Exponential(Vec<(f64, f64)>);
    impl LeastSquares for Exponential {
        fn residual_count(&self) -> usize {
            self.0.len()
        }
        fn residuals(&self, p: &[f64], r: &mut [f64]) {
            for (ri, (x, y)) in r.iter_mut().zip(&self.0) {
                *ri = p[0] * (p[1] * x).exp() + p[2] - y;
            }
        }
    }

    // A second formulation: the exact parameters of noise-free data, from a far start.
    #[test]
    fn exponential_fit_recovers_the_generating_parameters() {
        let data = (0..20)
            .map(|i| {
                let x = 0.1 * i as f64;
                (x, 2.5 * (-1.3 * x).exp() + 0.7)
            })
            .collect();
        let s = levenberg_marquardt(
            &Exponential(data),
            &[1.0, -0.1, 0.0],
            &LmSettings::default(),
        )
        .unwrap();
        for (got, want) in s.p.iter().zip([2.5, -1.3, 0.7]) {
            assert!((got - want).abs() < 1e-9, "{:?}", s);
        }
    }

    // Least squares with a residual at the optimum: the normal equations Jᵀr = 0 of a line fit
    // y = a + b x to non-collinear points are the closed-form regression.
    #[test]
    fn line_fit_matches_the_closed_form_regression() {
        struct Line(Vec<(f64, f64)>);
        impl LeastSquares for Line {
            fn residual_count(&self) -> usize {
                self.0.len()
            }
            fn residuals(&self, p: &[f64], r: &mut [f64]) {
                for (ri, (x, y)) in r.iter_mut().zip(&self.0) {
                    *ri = p[0] + p[1] * x - y;
                }
            }
        }
        let pts = vec![(0.0, 1.0), (1.0, 2.9), (2.0, 5.2), (3.0, 6.8), (4.0, 9.1)];
        let n = pts.len() as f64;
        let (sx, sy) = pts.iter().fold((0.0, 0.0), |s, p| (s.0 + p.0, s.1 + p.1));
        let sxx: f64 = pts.iter().map(|p| p.0 * p.0).sum();
        let sxy: f64 = pts.iter().map(|p| p.0 * p.1).sum();
        let b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
        let a = (sy - b * sx) / n;
        let s = levenberg_marquardt(&Line(pts), &[0.0, 0.0], &LmSettings::default()).unwrap();
        assert!(
            (s.p[0] - a).abs() < 1e-10 && (s.p[1] - b).abs() < 1e-10,
            "{s:?} vs {a} {b}"
        );
        assert!(s.cost > 0.0);
    }

    #[test]
    fn too_few_residuals_is_an_input_error() {
        let e = levenberg_marquardt(
            &Exponential(vec![(0.0, 1.0)]),
            &[1.0, 1.0, 1.0],
            &LmSettings::default(),
        )
        .unwrap_err();
        assert!(matches!(e, MbdError::InvalidInput { .. }), "{e}");
    }
}
