//! Kerkkänen's proposed planar linear shear-deformable ANCF beam (8 coordinates), §2.1.1–2.2.1.

use super::kernel::{QuadraticStrainBeam, QuadraticStrainKernel, StrainPoint};
use super::{ElementBody, NodeLayout};
use crate::error::{AncfError, check_positive};
use crate::material::Material;
use crate::section::Section;
use crate::shape::{self, LINEAR_BLOCKS};

/// The proposed 8-DOF linear beam: field (2.10), coordinates (2.11) `[r_I, r_{y,I}, r_J,
/// r_{y,J}]`, shape functions (2.12), Poisson-free energy (2.18)–(2.19) with shear correction
/// `k_s`, integrated in closed form over the cross-section and with **one Gauss point along
/// `x`** (the selective/reduced rule of §2.2.1 that removes shear locking; seed note §3.2.6).
pub type ProposedBeam = QuadraticStrainBeam<LINEAR_BLOCKS>;

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
        let c = material.poisson_free_matrix();
        Ok(Self {
            body: ElementBody {
                layout: NodeLayout::PositionCrossSlope,
                length,
                material,
                section,
            },
            kernel: QuadraticStrainKernel { points, c },
        })
    }

    /// Material of the element.
    pub fn material(&self) -> &Material {
        &self.body.material
    }
}
