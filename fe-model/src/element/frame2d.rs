//! Planar Euler–Bernoulli frame element (u, v, θ per node) with geometric stiffness.
//!
//! Local axes: x along the element, y normal to it. Local matrices (Przemieniecki; Cook et al.,
//! *Concepts and Applications of FEA*, ch. 2 and 18):
//! - stiffness: `EA/L [1 −1; −1 1]` on (u1, u2) and the Hermite bending block
//!   `EI/L³ [12 6L −12 6L; 6L 4L² −6L 2L²; −12 −6L 12 −6L; 6L 2L² −6L 4L²]` on (v1, θ1, v2, θ2);
//! - geometric stiffness of the axial force N (tension > 0), consistent with the cubic field:
//!   `N/(30L) [36 3L −36 3L; 3L 4L² −3L −L²; −36 −3L 36 −3L; 3L −L² −3L 4L²]`;
//! - consistent mass `ρA L/6 [2 1; 1 2]` axial and
//!   `ρA L/420 [156 22L 54 −13L; 22L 4L² 13L −3L²; 54 13L 156 −22L; −13L −3L² −22L 4L²]`;
//! - lumped mass by HRZ diagonal scaling: `ρA L/2` per translation, `ρA L³/78` per rotation.
//!
//! Global matrices are `Tᵀ k T` with the node rotation `[c s 0; −s c 0; 0 0 1]`.

use super::{FrameElement, MassKind, hermite};
use crate::FeError;
use faer::Mat;
use serde::{Deserialize, Serialize};

/// Section and material of a planar frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Frame2dSection {
    /// Axial stiffness EA \[N\].
    pub ea: f64,
    /// Bending stiffness EI \[N·m²\].
    pub ei: f64,
    /// Mass per unit length ρA \[kg/m\].
    pub mass_per_length: f64,
}

impl Frame2dSection {
    /// Validate the section (all values finite, EA and EI > 0, ρA ≥ 0).
    pub fn validate(&self) -> Result<(), FeError> {
        FeError::check_positive("ea", self.ea)?;
        FeError::check_positive("ei", self.ei)?;
        FeError::check_non_negative("mass_per_length", self.mass_per_length)?;
        Ok(())
    }
}

/// Two-node planar Euler–Bernoulli frame element.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame2d {
    /// Global DOFs (u1, v1, θ1, u2, v2, θ2).
    pub dofs: [usize; 6],
    /// Length L \[m\].
    pub length: f64,
    /// Direction cosine c = cos α.
    pub c: f64,
    /// Direction sine s = sin α.
    pub s: f64,
    /// Section.
    pub section: Frame2dSection,
    /// Axial force N \[N\] (tension positive) for the geometric stiffness.
    pub axial_force: f64,
}

impl Frame2d {
    /// New element between points `xa` and `xb` \[m\].
    pub fn new(
        dofs: [usize; 6], xa: [f64; 2], xb: [f64; 2], section: Frame2dSection, axial_force: f64,
    ) -> Result<Self, FeError> {
        section.validate()?;
        if !axial_force.is_finite() {
            return Err(FeError::param("axial_force", axial_force, "must be finite"));
        }
        let dx = xb[0] - xa[0];
        let dy = xb[1] - xa[1];
        let length = dx.hypot(dy);
        FeError::check_positive("frame element length", length)?;
        Ok(Self {
            dofs,
            length,
            c: dx / length,
            s: dy / length,
            section,
            axial_force,
        })
    }

    /// Scatter a 2×2 axial block and a 4×4 bending block into local 6×6 order.
    fn local(axial: [[f64; 2]; 2], bend: [[f64; 4]; 4]) -> Mat<f64> {
        let ax = [0usize, 3];
        let bd = [1usize, 2, 4, 5];
        let mut k = Mat::zeros(6, 6);
        for i in 0..2 {
            for j in 0..2 {
                k[(ax[i], ax[j])] = axial[i][j];
            }
        }
        for i in 0..4 {
            for j in 0..4 {
                k[(bd[i], bd[j])] = bend[i][j];
            }
        }
        k
    }
}

impl FrameElement for Frame2d {
    fn dofs(&self) -> &[usize] {
        &self.dofs
    }

    fn rotation(&self) -> Mat<f64> {
        let (c, s) = (self.c, self.s);
        let mut t = Mat::zeros(6, 6);
        for b in 0..2 {
            let o = 3 * b;
            t[(o, o)] = c;
            t[(o, o + 1)] = s;
            t[(o + 1, o)] = -s;
            t[(o + 1, o + 1)] = c;
            t[(o + 2, o + 2)] = 1.0;
        }
        t
    }

    fn local_stiffness(&self) -> Mat<f64> {
        let l = self.length;
        let a = self.section.ea / l;
        Self::local(
            [[a, -a], [-a, a]],
            hermite::bending_stiffness(self.section.ei, l, 0.0),
        )
    }

    fn local_mass(&self, kind: MassKind) -> Mat<f64> {
        let l = self.length;
        let m = self.section.mass_per_length * l;
        match kind {
            MassKind::Consistent => {
                let a = m / 6.0;
                Self::local([[2.0 * a, a], [a, 2.0 * a]], hermite::consistent_mass(m, l))
            }
            MassKind::Lumped => {
                let r = m * l * l / 78.0;
                let mut d = [[0.0; 4]; 4];
                d[0][0] = m / 2.0;
                d[1][1] = r;
                d[2][2] = m / 2.0;
                d[3][3] = r;
                Self::local([[m / 2.0, 0.0], [0.0, m / 2.0]], d)
            }
        }
    }

    fn local_geometric_stiffness(&self) -> Mat<f64> {
        Self::local(
            [[0.0; 2]; 2],
            hermite::geometric_stiffness(self.axial_force, self.length),
        )
    }
}
