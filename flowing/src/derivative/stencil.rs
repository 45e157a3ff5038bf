//! Finite-difference weights on arbitrary (non-uniform) point sets.

/// Weights `w[k][i]` such that `f^(k)(x0) ≈ Σ_i w[k][i] f(xs[i])` for `k = 0..=order`, exact for
/// polynomials of degree `xs.len() - 1` (Fornberg's recursion, Math. Comp. 51 (1988) 699–706).
///
/// This is the building block of the non-uniform stencils of Ribaric App. A.2 (A.1, A.2).
pub fn fd_weights(x0: f64, xs: &[f64], order: usize) -> Vec<Vec<f64>> {
    let n = xs.len();
    let mut c = vec![vec![0.0; n]; order + 1];
    if n == 0 {
        return c;
    }
    c[0][0] = 1.0;
    let mut c1 = 1.0;
    let mut c4 = xs[0] - x0;
    for i in 1..n {
        let mn = i.min(order);
        let mut c2 = 1.0;
        let c5 = c4;
        c4 = xs[i] - x0;
        for j in 0..i {
            let c3 = xs[i] - xs[j];
            c2 *= c3;
            if j == i - 1 {
                for k in (1..=mn).rev() {
                    c[k][i] = c1 * (k as f64 * c[k - 1][i - 1] - c5 * c[k][i - 1]) / c2;
                }
                c[0][i] = -c1 * c5 * c[0][i - 1] / c2;
            }
            for k in (1..=mn).rev() {
                c[k][j] = (c4 * c[k][j] - k as f64 * c[k - 1][j]) / c3;
            }
            c[0][j] = c4 * c[0][j] / c3;
        }
        c1 = c2;
    }
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: exactness on polynomials of degree n-1 (Fornberg 1988).
    #[test]
    fn weights_exact_on_cubics() {
        let xs = [0.1, 0.35, 0.5, 0.9];
        let x0 = 0.42;
        let w = fd_weights(x0, &xs, 2);
        let f = |x: f64| 1.0 - 2.0 * x + 3.0 * x * x - 0.7 * x * x * x;
        let df = |x: f64| -2.0 + 6.0 * x - 2.1 * x * x;
        let ddf = |x: f64| 6.0 - 4.2 * x;
        let apply = |k: usize| xs.iter().zip(&w[k]).map(|(x, w)| w * f(*x)).sum::<f64>();
        assert!((apply(0) - f(x0)).abs() < 1e-13);
        assert!((apply(1) - df(x0)).abs() < 1e-12);
        assert!((apply(2) - ddf(x0)).abs() < 1e-10);
    }
}
