//! The Omar–Shabana planar shear-deformable ANCF beam (12 coordinates), Kerkkänen §2.1.

use super::kernel::{QuadraticStrainBeam, QuadraticStrainKernel, StrainPoint};
use super::{ElementBody, NodeLayout};
use crate::error::{AncfError, check_positive, invalid};
use crate::material::Material;
use crate::section::Section;
use crate::shape::{self, CUBIC_BLOCKS};
use contact::GaussRule;

/// Omar–Shabana element: field (2.2), coordinates (2.8) `[r, r_x, r_y]` per node, shape
/// functions (3.11) with the corrected `S₅`, full plane continuum energy (2.16)–(2.17) with Lamé
/// constants (hence Poisson locking for `ν ≠ 0`), closed form over the cross-section and
/// **four Gauss points along `x`** (Kerkkänen §2.4; seed note §3.1).
pub type OmarShabanaBeam = QuadraticStrainBeam<CUBIC_BLOCKS>;

impl OmarShabanaBeam {
    /// Element of reference length `length` \[m\] with `gauss_x` points along the axis (4 in the
    /// thesis).
    pub fn with_rule(
        length: f64, material: Material, section: Section, gauss_x: usize,
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
        let c = material.continuum_matrix();
        Ok(Self {
            body: ElementBody {
                layout: NodeLayout::PositionBothSlopes,
                length,
                material,
                section,
            },
            kernel: QuadraticStrainKernel { points, c },
        })
    }

    /// Element with the thesis's 4-point rule along `x`.
    pub fn new(length: f64, material: Material, section: Section) -> Result<Self, AncfError> {
        Self::with_rule(length, material, section, 4)
    }
}
