//! Kerkkänen's proposed planar linear shear-deformable ANCF beam (8 coordinates), §2.1.1–2.2.1.

use super::kernel::{QuadraticStrainKernel, StrainPoint};
use super::{AncfElement, NodeLayout};
use crate::error::{AncfError, check_positive};
use crate::material::Material;
use crate::section::Section;
use crate::shape::{self, LINEAR_BLOCKS};

/// The proposed 8-DOF linear beam: field (2.10), coordinates (2.11) `[r_I, r_{y,I}, r_J,
/// r_{y,J}]`, shape functions (2.12), Poisson-free energy (2.18)–(2.19) with shear correction
/// `k_s`, integrated in closed form over the cross-section and with **one Gauss point along
/// `x`** (the selective/reduced rule of §2.2.1 that removes shear locking; seed note §3.2.6).
#[derive(Debug, Clone)]
pub struct ProposedBeam {
    length: f64,
    material: Material,
    section: Section,
    kernel: QuadraticStrainKernel<LINEAR_BLOCKS>,
}

impl ProposedBeam {
    /// Element of reference length `length` \[m\].
    pub fn new(length: f64, material: Material, section: Section) -> Result<Self, AncfError> {
        check_positive("proposed element: length", length, " m")?;
        material.validate()?;
        let x = 0.5 * length;
        let points = section
            .y_rule()
            .iter()
            .map(|&(y, wy)| {
                let s = shape::linear(length, x, y);
                StrainPoint {
                    w: length * wy,
                    sx: s.sx,
                    sy: s.sy,
                }
            })
            .collect();
        Ok(Self {
            length,
            material,
            section,
            kernel: QuadraticStrainKernel {
                points,
                c: material.poisson_free_matrix(),
            },
        })
    }

    /// Material of the element.
    pub fn material(&self) -> &Material {
        &self.material
    }
}

impl AncfElement for ProposedBeam {
    fn layout(&self) -> NodeLayout {
        NodeLayout::PositionCrossSlope
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
        s[..LINEAR_BLOCKS].copy_from_slice(&shape::linear(self.length, x, y).s);
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
