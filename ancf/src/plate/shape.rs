//! Shape functions of the 36-coordinate ANCF thin plate (Kerkkänen §4.3, (4.14)-(4.15);
//! Dufva & Shabana \[63\]).
//!
//! The thesis does not print the shape functions. Following the reading note (§3.6), the element
//! interpolates each Cartesian component with the 12-term incomplete cubic
//! `{1, ξ, η, ξη, ξ², η², ξ²η, ξη², ξ³, η³, ξ³η, ξη³}` (`ξ = x/a`, `η = y/b`), and the 12 scalar
//! shape functions are fixed by the nodal values `r`, `r_x`, `r_y` at the corners
//! A(0, 0), B(a, 0), C(a, b), D(0, b). Rather than transcribing the note's closed forms, the
//! coefficients are obtained by inverting the 12×12 interpolation matrix once per element size
//! (the note's "safer procedure"); the closed forms serve as an independent check in the tests.

use crate::error::{AncfError, invalid};
use faer::Mat;
use faer::prelude::Solve;

/// Exponents `(p, q)` of the monomials `ξ^p η^q` of the incomplete cubic.
const MONOMIALS: [(i32, i32); 12] = [
    (0, 0),
    (1, 0),
    (0, 1),
    (1, 1),
    (2, 0),
    (0, 2),
    (2, 1),
    (1, 2),
    (3, 0),
    (0, 3),
    (3, 1),
    (1, 3),
];

/// Corner coordinates `(ξ, η)` of the nodes A, B, C, D.
const CORNERS: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];

/// The shape functions `S_k` (`k = 3·node + kind`, kind 0: `r`, 1: `r_x`, 2: `r_y`) and their
/// derivatives at one point, with respect to the physical coordinates `x`, `y` \[m\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeValues {
    /// `S_k`.
    pub s: [f64; 12],
    /// `∂S_k/∂x` \[1/m\].
    pub sx: [f64; 12],
    /// `∂S_k/∂y` \[1/m\].
    pub sy: [f64; 12],
    /// `∂²S_k/∂x²` \[1/m²\].
    pub sxx: [f64; 12],
    /// `∂²S_k/∂x∂y` \[1/m²\].
    pub sxy: [f64; 12],
    /// `∂²S_k/∂y²` \[1/m²\].
    pub syy: [f64; 12],
}

/// Shape functions of a rectangular `a × b` thin-plate element (Kerkkänen (4.14)-(4.15)).
#[derive(Debug, Clone, PartialEq)]
pub struct PlateShape {
    a: f64,
    b: f64,
    /// `coef[j][k]`: coefficient of monomial `j` in shape function `k`.
    coef: [[f64; 12]; 12],
}

/// `d^n/dt^n t^p` evaluated at `t`.
fn dpow(t: f64, p: i32, n: i32) -> f64 {
    if n > p {
        return 0.0;
    }
    let mut c = 1.0;
    for i in 0..n {
        c *= (p - i) as f64;
    }
    c * t.powi(p - n)
}

impl PlateShape {
    /// Shape functions of an element of side lengths `a` (along x) and `b` (along y) \[m\].
    pub fn new(a: f64, b: f64) -> Result<Self, AncfError> {
        for (name, v) in [("a", a), ("b", b)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(
                    format!("plate element: side {name}"),
                    format!("must be a positive length in m, got {v}"),
                ));
            }
        }
        // Interpolation matrix: row = condition (node, kind), column = monomial.
        let amat = Mat::<f64>::from_fn(12, 12, |row, j| {
            let (xi, eta) = CORNERS[row / 3];
            let (p, q) = MONOMIALS[j];
            match row % 3 {
                0 => dpow(xi, p, 0) * dpow(eta, q, 0),
                1 => dpow(xi, p, 1) * dpow(eta, q, 0) / a,
                _ => dpow(xi, p, 0) * dpow(eta, q, 1) / b,
            }
        });
        // A C = I: column k of C holds the monomial coefficients of shape function k.
        let c = amat.partial_piv_lu().solve(Mat::<f64>::identity(12, 12));
        let mut coef = [[0.0; 12]; 12];
        for (j, row) in coef.iter_mut().enumerate() {
            for (k, v) in row.iter_mut().enumerate() {
                *v = c[(j, k)];
            }
        }
        if coef.iter().flatten().any(|v| !v.is_finite()) {
            return Err(invalid(
                "plate element: shape functions",
                format!("the interpolation matrix of a {a} m × {b} m element is singular"),
            ));
        }
        Ok(Self { a, b, coef })
    }

    /// Side length along x \[m\].
    pub fn a(&self) -> f64 {
        self.a
    }

    /// Side length along y \[m\].
    pub fn b(&self) -> f64 {
        self.b
    }

    /// Shape functions and derivatives at the local point `(x, y)`, `x ∈ [0, a]`, `y ∈ [0, b]` \[m\].
    pub fn eval(&self, x: f64, y: f64) -> ShapeValues {
        let (xi, eta) = (x / self.a, y / self.b);
        let (ia, ib) = (1.0 / self.a, 1.0 / self.b);
        let mut out = ShapeValues {
            s: [0.0; 12],
            sx: [0.0; 12],
            sy: [0.0; 12],
            sxx: [0.0; 12],
            sxy: [0.0; 12],
            syy: [0.0; 12],
        };
        for (j, &(p, q)) in MONOMIALS.iter().enumerate() {
            let (f0, f1, f2) = (dpow(xi, p, 0), dpow(xi, p, 1), dpow(xi, p, 2));
            let (g0, g1, g2) = (dpow(eta, q, 0), dpow(eta, q, 1), dpow(eta, q, 2));
            let m = [
                f0 * g0,
                f1 * g0 * ia,
                f0 * g1 * ib,
                f2 * g0 * ia * ia,
                f1 * g1 * ia * ib,
                f0 * g2 * ib * ib,
            ];
            for k in 0..12 {
                let c = self.coef[j][k];
                out.s[k] += c * m[0];
                out.sx[k] += c * m[1];
                out.sy[k] += c * m[2];
                out.sxx[k] += c * m[3];
                out.sxy[k] += c * m[4];
                out.syy[k] += c * m[5];
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Interpolation property: S_k reproduces the nodal value / slope it belongs to.
    #[test]
    fn kronecker_property_at_the_corners() {
        let sh = PlateShape::new(0.7, 0.3).unwrap();
        for (n, &(xi, eta)) in CORNERS.iter().enumerate() {
            let v = sh.eval(xi * 0.7, eta * 0.3);
            for k in 0..12 {
                let want = |kind: usize| if k == 3 * n + kind { 1.0 } else { 0.0 };
                assert!((v.s[k] - want(0)).abs() < 1e-12);
                assert!((v.sx[k] - want(1)).abs() < 1e-12);
                assert!((v.sy[k] - want(2)).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn bad_sides_are_rejected() {
        assert!(PlateShape::new(0.0, 1.0).is_err());
        assert!(PlateShape::new(1.0, f64::NAN).is_err());
    }
}
