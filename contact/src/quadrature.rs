//! Gauss–Legendre quadrature on an interval, used for distributed contact forces along elements
//! (Kerkkänen (3.27)) and, by the `ancf` crate, for element integrals.

/// A Gauss–Legendre rule on the unit interval `[0, 1]`: `∫₀¹ f(ξ) dξ ≈ Σ wᵢ f(ξᵢ)`.
///
/// An `n`-point rule integrates polynomials up to degree `2n − 1` exactly.
#[derive(Debug, Clone, PartialEq)]
pub struct GaussRule {
    /// Abscissae `ξᵢ ∈ (0, 1)`, ascending.
    pub points: Vec<f64>,
    /// Weights `wᵢ > 0`, summing to 1.
    pub weights: Vec<f64>,
}

impl GaussRule {
    /// The `n`-point Gauss–Legendre rule on `[0, 1]` (`n ≥ 1`; `n = 0` gives an empty rule).
    ///
    /// The nodes are the roots of the Legendre polynomial `Pₙ`, found by Newton's method from
    /// the Chebyshev-type initial guess `cos(π(i − ¼)/(n + ½))`; the weights are
    /// `2 / ((1 − x²) Pₙ'(x)²)` on `[−1, 1]`, halved for `[0, 1]`.
    pub fn new(n: usize) -> Self {
        let mut points = vec![0.0; n];
        let mut weights = vec![0.0; n];
        let nf = n as f64;
        for i in 0..n.div_ceil(2) {
            let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                let (p, d) = legendre(n, x);
                dp = d;
                let dx = p / d;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            let (_, d) = legendre(n, x);
            if d != 0.0 {
                dp = d;
            }
            let w = 2.0 / ((1.0 - x * x) * dp * dp);
            // x is the i-th largest root; map to [0, 1] (ascending order).
            points[n - 1 - i] = 0.5 * (1.0 + x);
            weights[n - 1 - i] = 0.5 * w;
            points[i] = 0.5 * (1.0 - x);
            weights[i] = 0.5 * w;
        }
        Self { points, weights }
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether the rule has no points.
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Iterator over `(ξᵢ, wᵢ)` pairs on `[0, 1]`.
    pub fn iter(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.points
            .iter()
            .copied()
            .zip(self.weights.iter().copied())
    }
}

/// Legendre polynomial `Pₙ(x)` and its derivative by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let mut p0 = 1.0;
    let mut p1 = x;
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let kf = k as f64;
        let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
        p0 = p1;
        p1 = p2;
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: exactness of an n-point rule for monomials of degree ≤ 2n − 1 (∫₀¹ ξᵏ = 1/(k+1)).
    #[test]
    fn exact_for_polynomials() {
        for n in 1..=12 {
            let r = GaussRule::new(n);
            for k in 0..(2 * n) {
                let s: f64 = r.iter().map(|(x, w)| w * x.powi(k as i32)).sum();
                assert!(
                    (s - 1.0 / (k as f64 + 1.0)).abs() < 1e-14,
                    "n={n} k={k} s={s}"
                );
            }
            // not exact for degree 2n (the error is visible in f64 for small n)
            if n > 6 {
                continue;
            }
            let k = 2 * n;
            let s: f64 = r.iter().map(|(x, w)| w * x.powi(k as i32)).sum();
            assert!((s - 1.0 / (k as f64 + 1.0)).abs() > 1e-12);
        }
    }

    // Reference: 2-point rule nodes ½ ∓ ½/√3 (textbook value).
    #[test]
    fn two_point_nodes() {
        let r = GaussRule::new(2);
        assert!((r.points[0] - (0.5 - 0.5 / 3f64.sqrt())).abs() < 1e-15);
        assert!((r.weights[1] - 0.5).abs() < 1e-15);
    }
}
