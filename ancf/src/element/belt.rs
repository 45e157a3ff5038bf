//! The planar belt element of Kerkkänen §3.1: the Dufva–Sopanen–Mikkola shear-deformable ANCF
//! beam (12 coordinates) with axial and bending stiffness multipliers `α₁`, `α₂`.

use super::belt_kernel::{self, Constants, KernelPoint};
use super::{AncfElement, ElementBody, NodeLayout};
use crate::autodiff::{Dual, Hyper, Real};
use crate::error::{AncfError, check_positive, invalid};
use crate::material::Material;
use crate::section::Section;
use crate::shape::{self, CUBIC_BLOCKS};
use ::belt::MaterialLaw;
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
    body: ElementBody,
    alpha1: f64,
    alpha2: f64,
    points: Vec<BeltPoint>,
    kernel_points: Vec<KernelPoint>,
    constants: Constants,
    law: MaterialLaw,
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
        length: f64, material: Material, section: Section, alpha1: f64, alpha2: f64, gauss_x: usize,
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
            law: MaterialLaw::StVenantKirchhoff,
        };
        Ok(Self {
            body: ElementBody {
                layout: NodeLayout::PositionBothSlopes,
                length,
                material,
                section,
            },
            alpha1,
            alpha2,
            points,
            kernel_points,
            constants,
            law: MaterialLaw::StVenantKirchhoff,
        })
    }

    /// The element with the material law `law` ([`MaterialLaw`], the belt's one law type;
    /// St Venant–Kirchhoff by default). In this element the law fixes how the axial force and
    /// the bending moment depend on the centreline stretch `λ = ‖r_{c,x}‖`:
    ///
    /// * [`MaterialLaw::StVenantKirchhoff`]: Kerkkänen (3.18)–(3.19), the Green strain (3.13)
    ///   with a constant `E`: axial force `N = α₁EA λ(λ² − 1)/2` in a straight span (12 % above
    ///   `α₁EA(λ − 1)` at 8 % strain), bending stiffness `α₂EI λ²`, and the bending–stretching
    ///   coupling `α₂EI λ(s² + ½c)` in the axial force on a curved belt;
    /// * [`MaterialLaw::Linear`]: linear in the engineering strain, `N = α₁EA(λ − 1)`, with the
    ///   bending moment `α₂EI s` independent of the stretch: what datasheets quote (`EA` as
    ///   force per unit strain) and what Exudyn's `ANCFCable2D` uses (its documentation:
    ///   `N = EA(‖r'‖ − 1)`, `M = EI K`, `K = (r' × r'')/‖r'‖²`, decoupled).
    ///
    /// The axial force of either law at a point is [`BeltElement::axial_force`].
    pub fn with_law(mut self, law: MaterialLaw) -> Self {
        self.law = law;
        self.constants.law = law;
        self
    }

    /// The material law.
    pub fn law(&self) -> MaterialLaw {
        self.law
    }

    /// Axial force \[N\] the element carries at `ξ = x/l ∈ [0, 1]` with coordinates `e`, from its
    /// own material law: `N = ∂W/∂λ` with `W` the energy per unit length ((3.18)–(3.19) or the
    /// linear law, [`MaterialLaw`]) and `λ = ‖r_{c,x}‖`, at fixed material curvature, shear angle
    /// and transverse strain. St Venant–Kirchhoff:
    /// `N = α₁EA λ(λ² − 1)/2 + α₂EI₂ λ(s² + ½c) + k_sGα₂A λ sin²γ` (the second term is the
    /// bending–stretching coupling of (3.18), ≈ 1.5 α₂EI κ² on a wrap of curvature κ; the third
    /// is second order in the shear angle); linear: `N = α₁EA(λ − 1) + k_sGα₂A λ sin²γ`. It is
    /// the tangential component of the section force, so `dN/ds = −f_t` and `N κ = f_n` (per
    /// unit length) hold along a wrap where the shear force is constant.
    pub fn axial_force(&self, e: &[f64], xi: f64) -> f64 {
        let x = xi * self.body.length;
        let p = KernelPoint {
            xi,
            w: 0.0,
            sx: shape::cubic(self.body.length, x, 0.0).sx,
            sxx: shape::cubic_xx(self.body.length, x),
        };
        belt_kernel::axial_force(&self.constants, self.body.length, &p, e)
    }

    /// Axial force from the reference energy ([`Self::strain_energy_reference`]'s density, by
    /// automatic differentiation of `W(μ r_{c,x}, μ r_{c,xx})` in `μ` at `μ = 1`, which
    /// stretches the section without changing `k`, `sin γ`, `(sin γ)_x`, `ε_yy`): the
    /// reference of [`Self::axial_force`] \[N\].
    pub fn axial_force_reference(&self, e: &[f64], xi: f64) -> f64 {
        let x = xi * self.body.length;
        let sx = shape::cubic(self.body.length, x, 0.0).sx;
        let sxx = shape::cubic_xx(self.body.length, x);
        let mut ev = [0.0; N];
        ev.copy_from_slice(&e[..N]);
        let nt = Self::nodal(&ev);
        let comb = |c: &[f64; CUBIC_BLOCKS], k: usize| -> f64 {
            (0..CUBIC_BLOCKS).map(|b| c[b] * ev[2 * b + k]).sum()
        };
        let mu = Dual::<1>::var(1.0, 0);
        let cst = |v: f64| Dual::<1>::cst(v);
        let prim = [
            mu * cst(comb(&sx, 0)),
            mu * cst(comb(&sx, 1)),
            mu * cst(comb(&sxx, 0)),
            mu * cst(comb(&sxx, 1)),
            cst(nt.sg_i * (1.0 - xi) + nt.sg_j * xi),
            cst((nt.sg_j - nt.sg_i) / self.body.length),
            cst(nt.ny_i * (1.0 - xi) + nt.ny_j * xi - 1.0),
        ];
        let w = self.density_primary(&prim);
        let lam = (comb(&sx, 0).powi(2) + comb(&sx, 1).powi(2)).sqrt();
        // dW/dμ = ∂W/∂λ · λ
        w.g[0] / lam
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
            (nt.sg_j - nt.sg_i).scale(1.0 / self.body.length),
            nt.ny_i.scale(1.0 - xi) + nt.ny_j.scale(xi) - T::cst(1.0),
        ];
        self.density_primary(&prim)
    }

    /// Energy per unit length as a function of the seven primary quantities at a point:
    /// `[r_{c,x}, r_{c,xx}, sin γ, (sin γ)_x, ε_yy]`, for the element's [`MaterialLaw`]
    /// (St Venant–Kirchhoff: (3.18)–(3.19) term by term; linear: `½α₁EA(‖r_{c,x}‖ − 1)²`
    /// and `½α₂EI (r_{c,x}ᵀr_{s,x})²/a` in place of the axial and bending terms).
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
        let (ee, s) = (self.body.material.young, &self.body.section);
        let g = self.body.material.shear_factor * self.body.material.shear_modulus();
        let am1 = a - T::cst(1.0);
        let (axial, bend) = match self.law {
            MaterialLaw::StVenantKirchhoff => (
                (am1 * am1).scale(self.alpha1 * s.area / 4.0),
                (b * b + (am1 * c).scale(0.5)).scale(self.alpha2 * s.i2)
                    + (c * c).scale(self.alpha2 * s.i4 / 4.0),
            ),
            // ½α₁EA(λ − 1)² and ½α₂EI s² with s² = b²/a (b = −√a s)
            MaterialLaw::Linear => {
                let lm1 = a.sqrt() - T::cst(1.0);
                (
                    (lm1 * lm1).scale(self.alpha1 * s.area),
                    (b * b * a.recip()).scale(self.alpha2 * s.i2),
                )
            }
        };
        let shear = (d * d).scale(s.area) + (f * f).scale(s.i2);
        (axial + bend).scale(0.5 * ee)
            + shear.scale(0.5 * g * self.alpha2)
            + (eyy * eyy).scale(0.5 * ee * s.area)
    }

    /// Tangent by second-order AD over all 12 coordinates at once (slow; the reference for the
    /// closed-form tangent of [`AncfElement::elastic_tangent`]).
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
    /// (the reference of the closed-form forces of [`AncfElement::elastic_forces`]).
    pub fn elastic_forces_reference(&self, e: &[f64], q: &mut [f64]) {
        let v: [Dual<N>; N] = std::array::from_fn(|k| Dual::var(e[k], k));
        let u = self.energy_generic(&v);
        for k in 0..N {
            q[k] = -u.g[k];
        }
    }

    /// Strain energy from the terms of (3.18)–(3.19) as written (reference of
    /// [`AncfElement::strain_energy`]) \[J\].
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

impl AncfElement for BeltElement {
    fn body(&self) -> &ElementBody {
        &self.body
    }
    fn strain_energy(&self, e: &[f64]) -> f64 {
        let mut q = [0.0; N];
        belt_kernel::evaluate(
            &self.constants,
            self.body.length,
            &self.kernel_points,
            e,
            &mut q,
            None,
        )
    }
    fn elastic_forces(&self, e: &[f64], q: &mut [f64]) {
        belt_kernel::evaluate(
            &self.constants,
            self.body.length,
            &self.kernel_points,
            e,
            q,
            None,
        );
    }
    fn elastic_tangent(&self, e: &[f64], q: &mut [f64], k: &mut [f64]) {
        belt_kernel::evaluate(
            &self.constants,
            self.body.length,
            &self.kernel_points,
            e,
            q,
            Some(k),
        );
    }
}
