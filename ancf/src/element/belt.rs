//! The planar belt element of Kerkkänen §3.1: the Dufva–Sopanen–Mikkola shear-deformable ANCF
//! beam (12 coordinates) with axial and bending stiffness multipliers `α₁`, `α₂`.

use super::{Element, NodeLayout};
use crate::autodiff::{Dual, Hyper, Real};
use crate::error::{AncfError, check_positive, invalid};
use crate::material::Material;
use crate::section::Section;
use crate::shape::{self, CUBIC_BLOCKS};
use contact::GaussRule;

const N: usize = 12;

/// Belt element (Kerkkänen §3.1).
///
/// Kinematics: `r_p = r_c + y r_s` (3.8), `r_c = S e|_{y=0}` (3.9) with the cubic shape
/// functions of (3.11) (`S₅` corrected), `r_s = (I + Ĩ sin γ) Ĩ t_ψ = n_ψ − sin γ t_ψ` (3.10),
/// `t_ψ = r_{c,x}/‖r_{c,x}‖` (3.4), `n_ψ = Ĩ t_ψ` (3.5), `sin γ` interpolated linearly between
/// the nodes (3.12).
///
/// Choices where the thesis refers to Dufva et al. (2005) (seed note §11, items 2–4):
/// * nodal shear angle `sin γᴵ = −t_ψ(x_I)·r_{y,I}/‖r_{y,I}‖` (so that `r_s ∥ r_y` at the nodes);
/// * transverse strain `ε_yy = (1 − ξ)‖r_yᴵ‖ + ξ‖r_yᴶ‖ − 1` (the 2-D form of (4.36)), energy
///   `½∫E ε_yy² dV`, not scaled by `α₁, α₂`;
/// * energy (3.18) + (3.19) integrated exactly over the section and with `gauss_x` Gauss points
///   along `x` (5 by default); `k_s` from the material;
/// * mass matrix (2.26) with the full shape functions (3.11), including the `r_y` rotary terms.
#[derive(Debug, Clone)]
pub struct BeltElement {
    length: f64,
    material: Material,
    section: Section,
    alpha1: f64,
    alpha2: f64,
    points: Vec<BeltPoint>,
}

#[derive(Debug, Clone, Copy)]
struct BeltPoint {
    xi: f64,
    w: f64,
    sx: [f64; CUBIC_BLOCKS],
    sxx: [f64; CUBIC_BLOCKS],
}

struct NodalTerms<T> {
    sg_i: T,
    sg_j: T,
    ny_i: T,
    ny_j: T,
}

impl BeltElement {
    /// Element of reference length `length` \[m\] with multipliers `alpha1` (axial) and `alpha2`
    /// (bending and shear), and `gauss_x` Gauss points along the axis.
    pub fn new(
        length: f64,
        material: Material,
        section: Section,
        alpha1: f64,
        alpha2: f64,
        gauss_x: usize,
    ) -> Result<Self, AncfError> {
        check_positive("belt element: length", length, " m")?;
        check_positive("belt element: alpha1", alpha1, "")?;
        check_positive("belt element: alpha2", alpha2, "")?;
        if gauss_x == 0 {
            return Err(invalid("belt element: gauss_x", "needs at least one point"));
        }
        material.validate()?;
        let rule = GaussRule::new(gauss_x);
        let points = rule
            .iter()
            .map(|(xi, w)| BeltPoint {
                xi,
                w: w * length,
                sx: shape::cubic(length, xi * length, 0.0).sx,
                sxx: shape::cubic_xx(length, xi * length),
            })
            .collect();
        Ok(Self {
            length,
            material,
            section,
            alpha1,
            alpha2,
            points,
        })
    }

    /// Axial multiplier `α₁`.
    pub fn alpha1(&self) -> f64 {
        self.alpha1
    }

    /// Bending/shear multiplier `α₂`.
    pub fn alpha2(&self) -> f64 {
        self.alpha2
    }

    fn nodal<T: Real>(e: &[T; N]) -> NodalTerms<T> {
        let one = |rx: [T; 2], ry: [T; 2]| {
            let nx = (rx[0] * rx[0] + rx[1] * rx[1]).sqrt();
            let ny = (ry[0] * ry[0] + ry[1] * ry[1]).sqrt();
            let sg = -((rx[0] * ry[0] + rx[1] * ry[1]) * (nx * ny).recip());
            (sg, ny)
        };
        let (sg_i, ny_i) = one([e[2], e[3]], [e[4], e[5]]);
        let (sg_j, ny_j) = one([e[8], e[9]], [e[10], e[11]]);
        NodalTerms {
            sg_i,
            sg_j,
            ny_i,
            ny_j,
        }
    }

    /// Energy per unit length at a point, Kerkkänen (3.18)–(3.19) plus the `ε_yy` term.
    fn density<T: Real>(&self, e: &[T; N], nt: &NodalTerms<T>, p: &BeltPoint) -> T {
        let comb = |c: &[f64; CUBIC_BLOCKS], a: usize| {
            let mut s = T::cst(0.0);
            for k in 0..CUBIC_BLOCKS {
                if c[k] != 0.0 {
                    s = s + e[2 * k + a].scale(c[k]);
                }
            }
            s
        };
        let xi = p.xi;
        let prim = [
            comb(&p.sx, 0),
            comb(&p.sx, 1),
            comb(&p.sxx, 0),
            comb(&p.sxx, 1),
            nt.sg_i.scale(1.0 - xi) + nt.sg_j.scale(xi),
            (nt.sg_j - nt.sg_i).scale(1.0 / self.length),
            nt.ny_i.scale(1.0 - xi) + nt.ny_j.scale(xi) - T::cst(1.0),
        ];
        self.density_primary(&prim)
    }

    /// Energy per unit length as a function of the seven primary quantities at a point:
    /// `[r_{c,x}, r_{c,xx}, sin γ, (sin γ)_x, ε_yy]`.
    fn density_primary<T: Real>(&self, p: &[T; 7]) -> T {
        let rcx = [p[0], p[1]];
        let rcxx = [p[2], p[3]];
        let (sg, sgx, eyy) = (p[4], p[5], p[6]);
        let a = rcx[0] * rcx[0] + rcx[1] * rcx[1];
        let inv = a.sqrt().recip();
        let t = [rcx[0] * inv, rcx[1] * inv];
        let n = [-t[1], t[0]];
        let tdot = t[0] * rcxx[0] + t[1] * rcxx[1];
        let tx = [(rcxx[0] - t[0] * tdot) * inv, (rcxx[1] - t[1] * tdot) * inv];
        let nx = [-tx[1], tx[0]];
        let rs = [n[0] - sg * t[0], n[1] - sg * t[1]];
        let rsx = [
            nx[0] - sgx * t[0] - sg * tx[0],
            nx[1] - sgx * t[1] - sg * tx[1],
        ];
        let b = rcx[0] * rsx[0] + rcx[1] * rsx[1];
        let c = rsx[0] * rsx[0] + rsx[1] * rsx[1];
        let d = rcx[0] * rs[0] + rcx[1] * rs[1];
        let f = rsx[0] * rs[0] + rsx[1] * rs[1];
        let (ee, s) = (self.material.young, &self.section);
        let g = self.material.shear_factor * self.material.shear_modulus();
        let am1 = a - T::cst(1.0);
        let axial = (am1 * am1).scale(self.alpha1 * s.area / 4.0);
        let bend = (b * b + (am1 * c).scale(0.5)).scale(self.alpha2 * s.i2)
            + (c * c).scale(self.alpha2 * s.i4 / 4.0);
        let shear = (d * d).scale(s.area) + (f * f).scale(s.i2);
        (axial + bend).scale(0.5 * ee)
            + shear.scale(0.5 * g * self.alpha2)
            + (eyy * eyy).scale(0.5 * ee * s.area)
    }

    /// Tangent by second-order AD over all 12 coordinates at once (slow; the reference for the
    /// chain-rule tangent of [`Element::elastic_tangent`]).
    pub fn elastic_tangent_reference(&self, e: &[f64], q: &mut [f64], k: &mut [f64]) {
        let v: [Hyper<N>; N] = std::array::from_fn(|i| Hyper::linear(e[i], &[(i, 1.0)]));
        let u = self.energy_generic(&v);
        for i in 0..N {
            q[i] = -u.g[i];
            for j in 0..N {
                k[i + j * N] = u.h[i][j];
            }
        }
    }

    /// Chain-rule tangent: second-order AD over the 4 coordinates `(r_x, r_y)` of each node for
    /// the nodal shear angle and slope norm, and over the 7 primary quantities at each Gauss
    /// point; `H_e = Σ w (Jᵀ H_p J) + Σ (∂U/∂s) ∂²s/∂e²` for the nodal functions `s`.
    fn tangent_chain(&self, e: &[f64], q: &mut [f64], k: &mut [f64]) {
        let node = |off: usize| {
            let v: [Hyper<4>; 4] = std::array::from_fn(|i| Hyper::linear(e[off + i], &[(i, 1.0)]));
            let nx = (v[0] * v[0] + v[1] * v[1]).sqrt();
            let ny = (v[2] * v[2] + v[3] * v[3]).sqrt();
            let sg = -((v[0] * v[2] + v[1] * v[3]) * (nx * ny).recip());
            (sg, ny)
        };
        let (sgi, nyi) = node(2);
        let (sgj, nyj) = node(8);
        let l = self.length;
        let mut grad = [0.0; N];
        let mut h = [[0.0; N]; N];
        let mut coef = [0.0; 4]; // ∂U/∂(sg_i, ny_i, sg_j, ny_j)
        for pt in &self.points {
            let xi = pt.xi;
            let mut pv = [0.0; 7];
            for kk in 0..CUBIC_BLOCKS {
                pv[0] += pt.sx[kk] * e[2 * kk];
                pv[1] += pt.sx[kk] * e[2 * kk + 1];
                pv[2] += pt.sxx[kk] * e[2 * kk];
                pv[3] += pt.sxx[kk] * e[2 * kk + 1];
            }
            pv[4] = (1.0 - xi) * sgi.v + xi * sgj.v;
            pv[5] = (sgj.v - sgi.v) / l;
            pv[6] = (1.0 - xi) * nyi.v + xi * nyj.v - 1.0;
            let vars: [Hyper<7>; 7] = std::array::from_fn(|i| Hyper::linear(pv[i], &[(i, 1.0)]));
            let d = self.density_primary(&vars);
            // J = ∂p/∂e (7 × 12)
            let mut jac = [[0.0; N]; 7];
            for kk in 0..CUBIC_BLOCKS {
                jac[0][2 * kk] = pt.sx[kk];
                jac[1][2 * kk + 1] = pt.sx[kk];
                jac[2][2 * kk] = pt.sxx[kk];
                jac[3][2 * kk + 1] = pt.sxx[kk];
            }
            for i in 0..4 {
                jac[4][2 + i] = (1.0 - xi) * sgi.g[i];
                jac[4][8 + i] = xi * sgj.g[i];
                jac[5][2 + i] = -sgi.g[i] / l;
                jac[5][8 + i] = sgj.g[i] / l;
                jac[6][2 + i] = (1.0 - xi) * nyi.g[i];
                jac[6][8 + i] = xi * nyj.g[i];
            }
            let w = pt.w;
            // grad += w Jᵀ g ; hj = H_p J (7 × 12) ; h += w Jᵀ hj
            let mut hj = [[0.0; N]; 7];
            for a in 0..7 {
                for c in 0..N {
                    let mut acc = 0.0;
                    for b in 0..7 {
                        acc += d.h[a][b] * jac[b][c];
                    }
                    hj[a][c] = acc;
                }
            }
            for c in 0..N {
                let mut gacc = 0.0;
                for a in 0..7 {
                    gacc += jac[a][c] * d.g[a];
                }
                grad[c] += w * gacc;
                for r in 0..N {
                    let mut acc = 0.0;
                    for a in 0..7 {
                        acc += jac[a][r] * hj[a][c];
                    }
                    h[r][c] += w * acc;
                }
            }
            coef[0] += w * ((1.0 - xi) * d.g[4] - d.g[5] / l);
            coef[2] += w * (xi * d.g[4] + d.g[5] / l);
            coef[1] += w * (1.0 - xi) * d.g[6];
            coef[3] += w * xi * d.g[6];
        }
        for i in 0..4 {
            for j in 0..4 {
                h[2 + i][2 + j] += coef[0] * sgi.h[i][j] + coef[1] * nyi.h[i][j];
                h[8 + i][8 + j] += coef[2] * sgj.h[i][j] + coef[3] * nyj.h[i][j];
            }
        }
        for i in 0..N {
            q[i] = -grad[i];
            for j in 0..N {
                k[i + j * N] = h[i][j];
            }
        }
    }

    fn energy_generic<T: Real>(&self, e: &[T; N]) -> T {
        let nt = Self::nodal(e);
        let mut u = T::cst(0.0);
        for p in &self.points {
            u = u + self.density(e, &nt, p).scale(p.w);
        }
        u
    }
}

impl Element for BeltElement {
    fn layout(&self) -> NodeLayout {
        NodeLayout::PositionBothSlopes
    }
    fn length(&self) -> f64 {
        self.length
    }
    fn density(&self) -> f64 {
        self.material.density
    }
    fn section(&self) -> &Section {
        &self.section
    }
    fn shape(&self, x: f64, y: f64, s: &mut [f64]) {
        s[..CUBIC_BLOCKS].copy_from_slice(&shape::cubic(self.length, x, y).s);
    }
    fn strain_energy(&self, e: &[f64]) -> f64 {
        let mut v = [0.0; N];
        v.copy_from_slice(&e[..N]);
        self.energy_generic(&v)
    }
    fn elastic_forces(&self, e: &[f64], q: &mut [f64]) {
        let v: [Dual<N>; N] = std::array::from_fn(|k| Dual::var(e[k], k));
        let u = self.energy_generic(&v);
        for k in 0..N {
            q[k] = -u.g[k];
        }
    }
    fn elastic_tangent(&self, e: &[f64], q: &mut [f64], k: &mut [f64]) {
        self.tangent_chain(e, q, k)
    }
}
