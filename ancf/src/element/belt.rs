//! The planar belt element of Kerkkänen §3.1: the Dufva–Sopanen–Mikkola shear-deformable ANCF
//! beam (12 coordinates) with axial and bending stiffness multipliers `α₁`, `α₂`.

use super::belt_kernel::{self, Constants, KernelPoint};
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
///
/// Forces and tangent are evaluated in closed form (module `belt_kernel`: the energy density is
/// a polynomial in five scalars per Gauss point); the energy written out term by term as in
/// (3.18)–(3.19) with automatic differentiation is kept as the reference
/// ([`BeltElement::elastic_forces_reference`], [`BeltElement::elastic_tangent_reference`]).
#[derive(Debug, Clone)]
pub struct BeltElement {
    length: f64,
    material: Material,
    section: Section,
    alpha1: f64,
    alpha2: f64,
    points: Vec<BeltPoint>,
    kernel_points: Vec<KernelPoint>,
    constants: Constants,
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
        let points: Vec<BeltPoint> = rule
            .iter()
            .map(|(xi, w)| BeltPoint {
                xi,
                w: w * length,
                sx: shape::cubic(length, xi * length, 0.0).sx,
                sxx: shape::cubic_xx(length, xi * length),
            })
            .collect();
        let kernel_points = points
            .iter()
            .map(|p| KernelPoint {
                xi: p.xi,
                w: p.w,
                sx: p.sx,
                sxx: p.sxx,
            })
            .collect();
        let e = material.young;
        let g = material.shear_factor * material.shear_modulus() * alpha2;
        let constants = Constants {
            c: [
                e * alpha1 * section.area / 8.0,
                0.5 * e * alpha2 * section.i2,
                e * alpha2 * section.i4 / 8.0,
                0.5 * g * section.area,
                0.5 * g * section.i2,
                0.5 * e * section.area,
            ],
        };
        Ok(Self {
            length,
            material,
            section,
            alpha1,
            alpha2,
            points,
            kernel_points,
            constants,
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
    /// closed-form tangent of [`Element::elastic_tangent`]).
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

    /// Forces `q = −∂U/∂e` by first-order AD of the energy (3.18)–(3.19) written term by term
    /// (the reference of the closed-form forces of [`Element::elastic_forces`]).
    pub fn elastic_forces_reference(&self, e: &[f64], q: &mut [f64]) {
        let v: [Dual<N>; N] = std::array::from_fn(|k| Dual::var(e[k], k));
        let u = self.energy_generic(&v);
        for k in 0..N {
            q[k] = -u.g[k];
        }
    }

    /// Strain energy from the terms of (3.18)–(3.19) as written (reference of
    /// [`Element::strain_energy`]) \[J\].
    pub fn strain_energy_reference(&self, e: &[f64]) -> f64 {
        let mut v = [0.0; N];
        v.copy_from_slice(&e[..N]);
        self.energy_generic(&v)
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
        let mut q = [0.0; N];
        belt_kernel::evaluate(
            &self.constants,
            self.length,
            &self.kernel_points,
            e,
            &mut q,
            None,
        )
    }
    fn elastic_forces(&self, e: &[f64], q: &mut [f64]) {
        belt_kernel::evaluate(
            &self.constants,
            self.length,
            &self.kernel_points,
            e,
            q,
            None,
        );
    }
    fn elastic_tangent(&self, e: &[f64], q: &mut [f64], k: &mut [f64]) {
        belt_kernel::evaluate(
            &self.constants,
            self.length,
            &self.kernel_points,
            e,
            q,
            Some(k),
        );
    }
}
