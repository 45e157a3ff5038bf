//! Shared evaluation kernel for elements whose Green–Lagrange strains are quadratic in the
//! nodal coordinates (the proposed and the Omar–Shabana beam): at each integration point
//! `r_x = S_x e`, `r_y = S_y e`, `ε = [½(r_x·r_x − 1), ½(r_y·r_y − 1), r_x·r_y]` (Kerkkänen
//! (2.14)–(2.15) with `J₀ = I`), energy density `½ εᵀ C ε`.
//!
//! Gradient: `∂U/∂e = Σ w σ_k ∂ε_k/∂e`, `σ = Cε`; tangent
//! `Σ w [ (∂ε/∂e)ᵀ C (∂ε/∂e) + σ_k ∂²ε_k/∂e² ]`, both exact.

use super::{AncfElement, ElementBody};

/// One integration point: weight (including `dx·dA`) and shape derivatives.
#[derive(Debug, Clone, Copy)]
pub(crate) struct StrainPoint<const N: usize> {
    pub w: f64,
    pub sx: [f64; N],
    pub sy: [f64; N],
}

/// Quadratic-strain kernel over a fixed set of integration points.
#[derive(Debug, Clone)]
pub(crate) struct QuadraticStrainKernel<const N: usize> {
    pub points: Vec<StrainPoint<N>>,
    pub c: [[f64; 3]; 3],
}

impl<const N: usize> QuadraticStrainKernel<N> {
    #[inline]
    fn kinematics(p: &StrainPoint<N>, e: &[f64]) -> ([f64; 2], [f64; 2]) {
        let mut rx = [0.0; 2];
        let mut ry = [0.0; 2];
        for k in 0..N {
            rx[0] += p.sx[k] * e[2 * k];
            rx[1] += p.sx[k] * e[2 * k + 1];
            ry[0] += p.sy[k] * e[2 * k];
            ry[1] += p.sy[k] * e[2 * k + 1];
        }
        (rx, ry)
    }

    #[inline]
    fn strain(rx: [f64; 2], ry: [f64; 2]) -> [f64; 3] {
        [
            0.5 * (rx[0] * rx[0] + rx[1] * rx[1] - 1.0),
            0.5 * (ry[0] * ry[0] + ry[1] * ry[1] - 1.0),
            rx[0] * ry[0] + rx[1] * ry[1],
        ]
    }

    #[inline]
    fn stress(&self, eps: [f64; 3]) -> [f64; 3] {
        let c = &self.c;
        [
            c[0][0] * eps[0] + c[0][1] * eps[1] + c[0][2] * eps[2],
            c[1][0] * eps[0] + c[1][1] * eps[1] + c[1][2] * eps[2],
            c[2][0] * eps[0] + c[2][1] * eps[1] + c[2][2] * eps[2],
        ]
    }

    /// Strain energy \[J\].
    pub fn energy(&self, e: &[f64]) -> f64 {
        let mut u = 0.0;
        for p in &self.points {
            let (rx, ry) = Self::kinematics(p, e);
            let eps = Self::strain(rx, ry);
            let sig = self.stress(eps);
            u += 0.5 * p.w * (eps[0] * sig[0] + eps[1] * sig[1] + eps[2] * sig[2]);
        }
        u
    }

    /// `q = −∂U/∂e`.
    pub fn forces(&self, e: &[f64], q: &mut [f64]) {
        q[..2 * N].fill(0.0);
        for p in &self.points {
            let (rx, ry) = Self::kinematics(p, e);
            let sig = self.stress(Self::strain(rx, ry));
            for k in 0..N {
                for a in 0..2 {
                    let g = sig[0] * p.sx[k] * rx[a]
                        + sig[1] * p.sy[k] * ry[a]
                        + sig[2] * (p.sx[k] * ry[a] + p.sy[k] * rx[a]);
                    q[2 * k + a] -= p.w * g;
                }
            }
        }
    }

    /// `q = −∂U/∂e` and `k = ∂²U/∂e²` (column-major `2N × 2N`).
    pub fn tangent(&self, e: &[f64], q: &mut [f64], k: &mut [f64]) {
        let n = 2 * N;
        q[..n].fill(0.0);
        k[..n * n].fill(0.0);
        let c = &self.c;
        for p in &self.points {
            let (rx, ry) = Self::kinematics(p, e);
            let sig = self.stress(Self::strain(rx, ry));
            // ∂ε_m/∂e at coordinate (block i, component a)
            let mut g = [[0.0; 3]; crate::element::MAX_NDOF];
            for i in 0..N {
                for a in 0..2 {
                    let row = &mut g[2 * i + a];
                    row[0] = p.sx[i] * rx[a];
                    row[1] = p.sy[i] * ry[a];
                    row[2] = p.sx[i] * ry[a] + p.sy[i] * rx[a];
                    q[2 * i + a] -= p.w * (sig[0] * row[0] + sig[1] * row[1] + sig[2] * row[2]);
                }
            }
            // C·∂ε/∂e per column
            let mut cg = [[0.0; 3]; crate::element::MAX_NDOF];
            for (cgj, gj) in cg.iter_mut().zip(g.iter()).take(n) {
                for m in 0..3 {
                    cgj[m] = c[m][0] * gj[0] + c[m][1] * gj[1] + c[m][2] * gj[2];
                }
            }
            for j in 0..n {
                let col = &mut k[j * n..(j + 1) * n];
                let cgj = cg[j];
                for (i, gi) in g.iter().enumerate().take(n) {
                    col[i] += p.w * (gi[0] * cgj[0] + gi[1] * cgj[1] + gi[2] * cgj[2]);
                }
            }
            for i in 0..N {
                for j in 0..N {
                    let v = p.w
                        * (sig[0] * p.sx[i] * p.sx[j]
                            + sig[1] * p.sy[i] * p.sy[j]
                            + sig[2] * (p.sx[i] * p.sy[j] + p.sy[i] * p.sx[j]));
                    k[2 * i + 2 * j * n] += v;
                    k[2 * i + 1 + (2 * j + 1) * n] += v;
                }
            }
        }
    }
}

/// A planar element whose strain energy is this module's quadratic-strain kernel: the
/// Omar–Shabana beam ([`super::OmarShabanaBeam`], `N = 6` cubic blocks, full continuum energy
/// (2.16)–(2.17)) and
/// the proposed beam ([`super::ProposedBeam`], `N = 4` linear blocks, Poisson-free energy
/// (2.18)–(2.19)), with the elastic forces (2.20) and their exact tangent. Each is built by its
/// own constructor, which fixes the integration points and the material matrix.
#[derive(Debug, Clone)]
pub struct QuadraticStrainBeam<const N: usize> {
    pub(crate) body: ElementBody,
    pub(crate) kernel: QuadraticStrainKernel<N>,
}

impl<const N: usize> AncfElement for QuadraticStrainBeam<N> {
    fn body(&self) -> &ElementBody {
        &self.body
    }
    fn strain_energy(&self, e: &[f64]) -> f64 {
        self.kernel.energy(e)
    }
    fn elastic_forces(&self, e: &[f64], q: &mut [f64]) {
        self.kernel.forces(e, q)
    }
    fn elastic_tangent(&self, e: &[f64], q: &mut [f64], k: &mut [f64]) {
        self.kernel.tangent(e, q, k)
    }
}
