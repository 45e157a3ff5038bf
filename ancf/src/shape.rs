//! Shape functions of the planar ANCF elements: `r(x, y) = Σₖ Sₖ(x, y) eₖ`, where `eₖ` are the
//! 2-vector nodal coordinates (positions and gradients) and `Sₖ` scalars (`S = [S₁I, S₂I, …]`).

/// Number of 2-vector blocks of the proposed linear element (r, r_y per node).
pub const LINEAR_BLOCKS: usize = 4;
/// Number of 2-vector blocks of the cubic elements (r, r_x, r_y per node).
pub const CUBIC_BLOCKS: usize = 6;

/// Scalar shape functions and their `x`, `y` derivatives at a point.
#[derive(Debug, Clone, Copy)]
pub struct ShapeEval<const N: usize> {
    /// `Sₖ(x, y)`.
    pub s: [f64; N],
    /// `∂Sₖ/∂x`.
    pub sx: [f64; N],
    /// `∂Sₖ/∂y`.
    pub sy: [f64; N],
}

/// Kerkkänen (2.12): `S₁ = 1 − ξ`, `S₂ = y(1 − ξ)`, `S₃ = ξ`, `S₄ = yξ` with `ξ = x/l`; block
/// order `r_I, r_{y,I}, r_J, r_{y,J}`.
pub fn linear(l: f64, x: f64, y: f64) -> ShapeEval<LINEAR_BLOCKS> {
    let xi = x / l;
    ShapeEval {
        s: [1.0 - xi, y * (1.0 - xi), xi, y * xi],
        sx: [-1.0 / l, -y / l, 1.0 / l, y / l],
        sy: [0.0, 1.0 - xi, 0.0, xi],
    }
}

/// Kerkkänen (3.11) with the misprinted `S₅` corrected to `l(ξ³ − ξ²)` (the printed
/// `l(−2ξ² + ξ³)` does not vanish at `ξ = 1`; the corrected one reproduces (2.9), see the
/// seed note §3.1): `S₁ = 1 − 3ξ² + 2ξ³`, `S₂ = l(ξ − 2ξ² + ξ³)`, `S₃ = y(1 − ξ)`,
/// `S₄ = 3ξ² − 2ξ³`, `S₅ = l(ξ³ − ξ²)`, `S₆ = yξ`; block order `r_I, r_{x,I}, r_{y,I}, r_J,
/// r_{x,J}, r_{y,J}` (also the Omar–Shabana element, Kerkkänen §2.1).
pub fn cubic(l: f64, x: f64, y: f64) -> ShapeEval<CUBIC_BLOCKS> {
    let xi = x / l;
    let xi2 = xi * xi;
    let xi3 = xi2 * xi;
    ShapeEval {
        s: [
            1.0 - 3.0 * xi2 + 2.0 * xi3,
            l * (xi - 2.0 * xi2 + xi3),
            y * (1.0 - xi),
            3.0 * xi2 - 2.0 * xi3,
            l * (xi3 - xi2),
            y * xi,
        ],
        sx: [
            (-6.0 * xi + 6.0 * xi2) / l,
            1.0 - 4.0 * xi + 3.0 * xi2,
            -y / l,
            (6.0 * xi - 6.0 * xi2) / l,
            3.0 * xi2 - 2.0 * xi,
            y / l,
        ],
        sy: [0.0, 0.0, 1.0 - xi, 0.0, 0.0, xi],
    }
}

/// Second `x` derivative of the cubic shape functions on the centreline `y = 0`
/// (needed by the belt element's curvature terms).
pub fn cubic_xx(l: f64, x: f64) -> [f64; CUBIC_BLOCKS] {
    let xi = x / l;
    [
        (-6.0 + 12.0 * xi) / (l * l),
        (-4.0 + 6.0 * xi) / l,
        0.0,
        (6.0 - 12.0 * xi) / (l * l),
        (6.0 * xi - 2.0) / l,
        0.0,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: interpolation property at the nodes (each block reproduces its nodal value).
    #[test]
    fn cubic_interpolates_nodal_coordinates() {
        let l = 0.7;
        let a = cubic(l, 0.0, 0.0);
        let b = cubic(l, l, 0.0);
        assert_eq!(a.s, [1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert!(
            b.s.iter()
                .zip([0.0, 0.0, 0.0, 1.0, 0.0, 0.0])
                .all(|(x, y)| (x - y).abs() < 1e-15)
        );
        assert!((a.sx[1] - 1.0).abs() < 1e-15 && (b.sx[4] - 1.0).abs() < 1e-15);
        assert!(
            b.sx.iter()
                .enumerate()
                .all(|(k, v)| k == 4 || v.abs() < 1e-14)
        );
        let c = cubic(l, 0.3, 0.2);
        assert!((c.sy[2] + c.sy[5] - 1.0).abs() < 1e-15);
    }

    // Reference: finite differences of the shape functions.
    #[test]
    fn derivatives_match_finite_differences() {
        let (l, x, y, h) = (1.3, 0.4, 0.05, 1e-6);
        let c = cubic(l, x, y);
        let cp = cubic(l, x + h, y);
        let cm = cubic(l, x - h, y);
        let xx = cubic_xx(l, x);
        for k in 0..6 {
            assert!(((cp.s[k] - cm.s[k]) / (2.0 * h) - c.sx[k]).abs() < 1e-8);
            let cp0 = cubic(l, x + h, 0.0);
            let cm0 = cubic(l, x - h, 0.0);
            assert!(((cp0.sx[k] - cm0.sx[k]) / (2.0 * h) - xx[k]).abs() < 1e-7);
        }
        let p = linear(l, x, y);
        let pp = linear(l, x, y + h);
        for k in 0..4 {
            assert!(((pp.s[k] - p.s[k]) / h - p.sy[k]).abs() < 1e-8);
        }
    }
}
