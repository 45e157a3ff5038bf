//! Small forward-mode automatic differentiation for element energies whose strain measures are
//! not polynomial in the nodal coordinates (the belt element, Kerkkänen §3.1). First-order
//! ([`Dual`]) and second-order ([`Hyper`]) numbers over `N` independent variables give exact
//! forces and an exact (analytic) tangent stiffness from one energy expression.

use std::ops::{Add, Mul, Neg, Sub};

/// Scalar operations needed by the element energies (implemented by `f64`, [`Dual`], [`Hyper`]).
pub trait Real:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Neg<Output = Self>
{
    /// A constant.
    fn cst(v: f64) -> Self;
    /// Multiplication by a constant.
    fn scale(self, s: f64) -> Self;
    /// Square root.
    fn sqrt(self) -> Self;
    /// Reciprocal.
    fn recip(self) -> Self;
    /// Value part.
    fn value(&self) -> f64;
}

impl Real for f64 {
    #[inline]
    fn cst(v: f64) -> Self {
        v
    }
    #[inline]
    fn scale(self, s: f64) -> Self {
        self * s
    }
    #[inline]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline]
    fn recip(self) -> Self {
        1.0 / self
    }
    #[inline]
    fn value(&self) -> f64 {
        *self
    }
}

/// First-order dual number: value and gradient with respect to `N` variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual<const N: usize> {
    /// Value.
    pub v: f64,
    /// Gradient.
    pub g: [f64; N],
}

impl<const N: usize> Dual<N> {
    /// The independent variable `k` with value `v`.
    pub fn var(v: f64, k: usize) -> Self {
        let mut g = [0.0; N];
        g[k] = 1.0;
        Self { v, g }
    }
    /// A linear combination `Σ cₖ xₖ` of the independent variables with coefficients `c`
    /// placed at indices `idx`.
    pub fn linear(v: f64, coeffs: &[(usize, f64)]) -> Self {
        let mut g = [0.0; N];
        for &(k, c) in coeffs {
            g[k] += c;
        }
        Self { v, g }
    }
    #[inline]
    fn chain(self, f: f64, df: f64) -> Self {
        let mut g = self.g;
        g.iter_mut().for_each(|x| *x *= df);
        Self { v: f, g }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline]
    fn add(mut self, o: Self) -> Self {
        self.v += o.v;
        for k in 0..N {
            self.g[k] += o.g[k];
        }
        self
    }
}
impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline]
    fn sub(mut self, o: Self) -> Self {
        self.v -= o.v;
        for k in 0..N {
            self.g[k] -= o.g[k];
        }
        self
    }
}
impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        self.scale(-1.0)
    }
}
impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        let mut g = [0.0; N];
        for k in 0..N {
            g[k] = self.v * o.g[k] + o.v * self.g[k];
        }
        Self { v: self.v * o.v, g }
    }
}
impl<const N: usize> Real for Dual<N> {
    #[inline]
    fn cst(v: f64) -> Self {
        Self { v, g: [0.0; N] }
    }
    #[inline]
    fn scale(mut self, s: f64) -> Self {
        self.v *= s;
        self.g.iter_mut().for_each(|x| *x *= s);
        self
    }
    #[inline]
    fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        self.chain(r, 0.5 / r)
    }
    #[inline]
    fn recip(self) -> Self {
        let r = 1.0 / self.v;
        self.chain(r, -r * r)
    }
    #[inline]
    fn value(&self) -> f64 {
        self.v
    }
}

/// Second-order number: value, gradient and (symmetric, full) Hessian over `N` variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hyper<const N: usize> {
    /// Value.
    pub v: f64,
    /// Gradient.
    pub g: [f64; N],
    /// Hessian (row-major, symmetric).
    pub h: [[f64; N]; N],
}

impl<const N: usize> Hyper<N> {
    /// A linear combination of the independent variables (zero Hessian).
    pub fn linear(v: f64, coeffs: &[(usize, f64)]) -> Self {
        let mut g = [0.0; N];
        for &(k, c) in coeffs {
            g[k] += c;
        }
        Self {
            v,
            g,
            h: [[0.0; N]; N],
        }
    }
    /// `f(self)` with `f' = df`, `f'' = d2f`.
    #[inline]
    fn chain(self, f: f64, df: f64, d2f: f64) -> Self {
        let mut out = self;
        out.v = f;
        for i in 0..N {
            for j in 0..N {
                out.h[i][j] = df * self.h[i][j] + d2f * self.g[i] * self.g[j];
            }
            out.g[i] = df * self.g[i];
        }
        out
    }
}

impl<const N: usize> Add for Hyper<N> {
    type Output = Self;
    #[inline]
    fn add(mut self, o: Self) -> Self {
        self.v += o.v;
        for i in 0..N {
            self.g[i] += o.g[i];
            for j in 0..N {
                self.h[i][j] += o.h[i][j];
            }
        }
        self
    }
}
impl<const N: usize> Sub for Hyper<N> {
    type Output = Self;
    #[inline]
    fn sub(mut self, o: Self) -> Self {
        self.v -= o.v;
        for i in 0..N {
            self.g[i] -= o.g[i];
            for j in 0..N {
                self.h[i][j] -= o.h[i][j];
            }
        }
        self
    }
}
impl<const N: usize> Neg for Hyper<N> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        self.scale(-1.0)
    }
}
impl<const N: usize> Mul for Hyper<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        let mut out = self;
        out.v = self.v * o.v;
        for i in 0..N {
            out.g[i] = self.v * o.g[i] + o.v * self.g[i];
            for j in 0..N {
                out.h[i][j] = self.v * o.h[i][j]
                    + o.v * self.h[i][j]
                    + self.g[i] * o.g[j]
                    + o.g[i] * self.g[j];
            }
        }
        out
    }
}
impl<const N: usize> Real for Hyper<N> {
    #[inline]
    fn cst(v: f64) -> Self {
        Self {
            v,
            g: [0.0; N],
            h: [[0.0; N]; N],
        }
    }
    #[inline]
    fn scale(mut self, s: f64) -> Self {
        self.v *= s;
        for i in 0..N {
            self.g[i] *= s;
            for j in 0..N {
                self.h[i][j] *= s;
            }
        }
        self
    }
    #[inline]
    fn sqrt(self) -> Self {
        let r = self.v.sqrt();
        self.chain(r, 0.5 / r, -0.25 / (r * self.v))
    }
    #[inline]
    fn recip(self) -> Self {
        let r = 1.0 / self.v;
        self.chain(r, -r * r, 2.0 * r * r * r)
    }
    #[inline]
    fn value(&self) -> f64 {
        self.v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: analytic derivatives of f(x, y) = sqrt(x) y / (1 + x y).
    #[test]
    fn hyper_matches_analytic_derivatives() {
        let (x0, y0) = (1.7, 0.4);
        let x = Hyper::<2>::linear(x0, &[(0, 1.0)]);
        let y = Hyper::<2>::linear(y0, &[(1, 1.0)]);
        let f = x.sqrt() * y * (Hyper::cst(1.0) + x * y).recip();
        let fv = |x: f64, y: f64| x.sqrt() * y / (1.0 + x * y);
        let h = 1e-4;
        assert!((f.v - fv(x0, y0)).abs() < 1e-15);
        let fx = (fv(x0 + h, y0) - fv(x0 - h, y0)) / (2.0 * h);
        let fy = (fv(x0, y0 + h) - fv(x0, y0 - h)) / (2.0 * h);
        assert!((f.g[0] - fx).abs() < 1e-8 && (f.g[1] - fy).abs() < 1e-8);
        let fxy = (fv(x0 + h, y0 + h) - fv(x0 + h, y0 - h) - fv(x0 - h, y0 + h)
            + fv(x0 - h, y0 - h))
            / (4.0 * h * h);
        let fxx = (fv(x0 + h, y0) - 2.0 * fv(x0, y0) + fv(x0 - h, y0)) / (h * h);
        assert!((f.h[0][1] - fxy).abs() < 1e-6 && (f.h[1][0] - fxy).abs() < 1e-6);
        assert!((f.h[0][0] - fxx).abs() < 1e-6);
        let d = Dual::<2>::var(x0, 0).sqrt() * Dual::var(y0, 1);
        assert!((d.g[0] - 0.5 * y0 / x0.sqrt()).abs() < 1e-15);
    }
}
