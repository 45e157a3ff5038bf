//! The Omar–Shabana planar shear-deformable ANCF beam (12 coordinates), Kerkkänen §2.1.

use super::kernel::{QuadraticStrainKernel, StrainPoint};
use super::{AncfElement, NodeLayout};
use crate::error::{AncfError, check_positive, invalid};
use crate::material::Material;
use crate::section::Section;
use crate::shape::{self, CUBIC_BLOCKS};
use contact::GaussRule;

/// Omar–Shabana element: field (2.2), coordinates (2.8) `[r, r_x, r_y]` per node, shape
/// functions (3.11) with the corrected `S₅`, full plane continuum energy (2.16)–(2.17) with Lamé
/// constants (hence Poisson locking for `ν ≠ 0`), closed form over the cross-section and
/// **four Gauss points along `x`** (Kerkkänen §2.4; seed note §3.1).
#[derive(Debug, Clone)]
pub struct OmarShabanaBeam {
    length: f64,
    material: Material,
    section: Section,
    kernel: QuadraticStrainKernel<CUBIC_BLOCKS>,
}

impl OmarShabanaBeam {
    /// Element of reference length `length` \[m\] with `gauss_x` points along the axis (4 in the
    /// thesis).
    pub fn with_rule(
        length: f64,
        material: Material,
        section: Section,
        gauss_x: usize,
    ) -> Result<Self, AncfError> {
        check_positive("Omar-Shabana element: length", length, " m")?;
        if gauss_x == 0 {
            return Err(invalid(
                "Omar-Shabana element: gauss_x",
                "needs at least one point",
            ));
        }
        material.validate()?;
        let rule = GaussRule::new(gauss_x);
        let mut points = Vec::with_capacity(3 * gauss_x);
        for (xi, wx) in rule.iter() {
            for (y, wy) in section.y_rule() {
                let s = shape::cubic(length, xi * length, y);
                points.push(StrainPoint {
                    w: wx * length * wy,
                    sx: s.sx,
                    sy: s.sy,
                });
            }
        }
        Ok(Self {
            length,
            material,
            section,
            kernel: QuadraticStrainKernel {
                points,
                c: material.continuum_matrix(),
            },
        })
    }

    /// Element with the thesis's 4-point rule along `x`.
    pub fn new(length: f64, material: Material, section: Section) -> Result<Self, AncfError> {
        Self::with_rule(length, material, section, 4)
    }
}

impl AncfElement for OmarShabanaBeam {
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
        self.kernel.energy(e)
    }
    fn elastic_forces(&self, e: &[f64], q: &mut [f64]) {
        self.kernel.forces(e, q)
    }
    fn elastic_tangent(&self, e: &[f64], q: &mut [f64], k: &mut [f64]) {
        self.kernel.tangent(e, q, k)
    }
}
