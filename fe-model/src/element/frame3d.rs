//! Spatial two-node frame element (6 DOFs per node: u, v, w, θx, θy, θz), Euler–Bernoulli or
//! Timoshenko.
//!
//! Local axes: x along the element, y from the orientation vector (its component normal to x),
//! z = x × y. Local matrices (Przemieniecki, *Theory of Matrix Structural Analysis*, §5.6 and
//! §11; Cook et al. ch. 2, 11 and 18), DOF order (u₁ v₁ w₁ θx₁ θy₁ θz₁ u₂ … θz₂):
//! - axial `EA/L`, torsion `GJ/L`;
//! - bending about z (v, θz) and about y (w, θy, with `w' = −θy`) with the shear-flexibility
//!   parameters `Φ = 12 EI/(κGA L²)` (Timoshenko; `Φ = 0` for Euler–Bernoulli), e.g.
//!   `EIz/((1+Φy)L³)·[12 6L −12 6L; 6L (4+Φy)L² −6L (2−Φy)L²; …]`;
//! - geometric stiffness of the axial force N in both bending planes,
//!   `N/(30L)[36 3L −36 3L; 3L 4L² −3L −L²; …]` (consistent Hermite form, as in 2D);
//! - consistent mass: axial and torsional `[2 1; 1 2]/6` blocks and the Hermite bending blocks
//!   `ρA L/420 [156 22L 54 −13L; …]` (the Euler–Bernoulli mass is used for both theories; the
//!   shear and rotary-inertia corrections to the mass are neglected);
//! - lumped mass (HRZ): `ρA L/2` per translation, `ρIp L/2` per torsion, `ρA L³/78` per
//!   bending rotation.

use super::{FrameElement, MassKind, hermite};
use crate::FeError;
use faer::Mat;
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Section and material of a spatial frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Frame3dSection {
    /// Axial stiffness EA \[N\].
    pub ea: f64,
    /// Bending stiffness about local y, EI_y \[N·m²\] (bending in the x–z plane).
    pub ei_y: f64,
    /// Bending stiffness about local z, EI_z \[N·m²\] (bending in the x–y plane).
    pub ei_z: f64,
    /// Torsional stiffness GJ \[N·m²\].
    pub gj: f64,
    /// Mass per unit length ρA \[kg/m\].
    pub mass_per_length: f64,
    /// Polar mass moment per unit length ρI_p \[kg·m\].
    pub polar_inertia_per_length: f64,
    /// Shear stiffness κGA for bending in the x–y plane \[N\]; `None` = Euler–Bernoulli.
    pub shear_y: Option<f64>,
    /// Shear stiffness κGA for bending in the x–z plane \[N\]; `None` = Euler–Bernoulli.
    pub shear_z: Option<f64>,
}

impl Frame3dSection {
    /// Validate (positive stiffnesses, non-negative masses).
    pub fn validate(&self) -> Result<(), FeError> {
        FeError::check_positive("ea", self.ea)?;
        FeError::check_positive("ei_y", self.ei_y)?;
        FeError::check_positive("ei_z", self.ei_z)?;
        FeError::check_positive("gj", self.gj)?;
        FeError::check_non_negative("mass_per_length", self.mass_per_length)?;
        FeError::check_non_negative("polar_inertia_per_length", self.polar_inertia_per_length)?;
        if let Some(s) = self.shear_y {
            FeError::check_positive("shear_y", s)?;
        }
        if let Some(s) = self.shear_z {
            FeError::check_positive("shear_z", s)?;
        }
        Ok(())
    }
}

/// Two-node spatial frame element.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame3d {
    /// Global DOFs (6 per node).
    pub dofs: [usize; 12],
    /// Length L \[m\].
    pub length: f64,
    /// Rows: local x, y, z unit vectors in global coordinates.
    pub axes: [[f64; 3]; 3],
    /// Section.
    pub section: Frame3dSection,
    /// Axial force N \[N\] (tension positive) for the geometric stiffness.
    pub axial_force: f64,
}

/// Indices of the four DOFs of a bending plane in the local 12-vector.
const XY: [usize; 4] = [1, 5, 7, 11];
const XZ: [usize; 4] = [2, 4, 8, 10];
/// Sign flips of the x–z plane (w' = −θy).
const XZ_SIGN: [f64; 4] = [1.0, -1.0, 1.0, -1.0];

impl Frame3d {
    /// New element between `xa` and `xb` \[m\]; `orientation` gives the local y direction (any
    /// vector not parallel to the element).
    pub fn new(
        dofs: [usize; 12], xa: [f64; 3], xb: [f64; 3], orientation: [f64; 3],
        section: Frame3dSection, axial_force: f64,
    ) -> Result<Self, FeError> {
        section.validate()?;
        if !axial_force.is_finite() {
            return Err(FeError::param("axial_force", axial_force, "must be finite"));
        }
        let d = Vector3::new(xb[0] - xa[0], xb[1] - xa[1], xb[2] - xa[2]);
        let length = d.norm();
        FeError::check_positive("frame element length", length)?;
        let ex = d / length;
        let o = Vector3::from(orientation);
        let oy = o - ex * o.dot(&ex);
        if oy.norm() <= 1e-9 * o.norm().max(1e-300) {
            return Err(FeError::param(
                "orientation",
                o.norm(),
                "must not be parallel to the element axis",
            ));
        }
        let ey = oy.normalize();
        let ez = ex.cross(&ey);
        Ok(Self {
            dofs,
            length,
            axes: [
                [ex[0], ex[1], ex[2]],
                [ey[0], ey[1], ey[2]],
                [ez[0], ez[1], ez[2]],
            ],
            section,
            axial_force,
        })
    }

    fn put2(k: &mut Mat<f64>, i: usize, j: usize, a: f64) {
        k[(i, i)] += a;
        k[(j, j)] += a;
        k[(i, j)] -= a;
        k[(j, i)] -= a;
    }

    fn put_bend(k: &mut Mat<f64>, idx: [usize; 4], sign: [f64; 4], b: [[f64; 4]; 4]) {
        for r in 0..4 {
            for c in 0..4 {
                k[(idx[r], idx[c])] += sign[r] * sign[c] * b[r][c];
            }
        }
    }
}

impl FrameElement for Frame3d {
    fn dofs(&self) -> &[usize] {
        &self.dofs
    }

    fn rotation(&self) -> Mat<f64> {
        let mut t = Mat::zeros(12, 12);
        for b in 0..4 {
            for i in 0..3 {
                for j in 0..3 {
                    t[(3 * b + i, 3 * b + j)] = self.axes[i][j];
                }
            }
        }
        t
    }

    fn local_stiffness(&self) -> Mat<f64> {
        let s = &self.section;
        let l = self.length;
        let mut k = Mat::zeros(12, 12);
        Self::put2(&mut k, 0, 6, s.ea / l);
        Self::put2(&mut k, 3, 9, s.gj / l);
        let phi_y = s.shear_y.map_or(0.0, |g| 12.0 * s.ei_z / (g * l * l));
        let phi_z = s.shear_z.map_or(0.0, |g| 12.0 * s.ei_y / (g * l * l));
        Self::put_bend(
            &mut k,
            XY,
            [1.0; 4],
            hermite::bending_stiffness(s.ei_z, l, phi_y),
        );
        Self::put_bend(
            &mut k,
            XZ,
            XZ_SIGN,
            hermite::bending_stiffness(s.ei_y, l, phi_z),
        );
        k
    }

    fn local_mass(&self, kind: MassKind) -> Mat<f64> {
        let s = &self.section;
        let l = self.length;
        let m = s.mass_per_length * l;
        let jp = s.polar_inertia_per_length * l;
        let mut k = Mat::zeros(12, 12);
        match kind {
            MassKind::Consistent => {
                for (i, j, t) in [(0usize, 6usize, m), (3, 9, jp)] {
                    k[(i, i)] += t / 3.0;
                    k[(j, j)] += t / 3.0;
                    k[(i, j)] += t / 6.0;
                    k[(j, i)] += t / 6.0;
                }
                let mb = hermite::consistent_mass(m, l);
                Self::put_bend(&mut k, XY, [1.0; 4], mb);
                Self::put_bend(&mut k, XZ, XZ_SIGN, mb);
            }
            MassKind::Lumped => {
                let r = m * l * l / 78.0;
                let diag = [
                    m / 2.0,
                    m / 2.0,
                    m / 2.0,
                    jp / 2.0,
                    r,
                    r,
                    m / 2.0,
                    m / 2.0,
                    m / 2.0,
                    jp / 2.0,
                    r,
                    r,
                ];
                for (i, d) in diag.iter().enumerate() {
                    k[(i, i)] = *d;
                }
            }
        }
        k
    }

    fn local_geometric_stiffness(&self) -> Mat<f64> {
        let l = self.length;
        let b = hermite::geometric_stiffness(self.axial_force, l);
        let mut k = Mat::zeros(12, 12);
        Self::put_bend(&mut k, XY, [1.0; 4], b);
        Self::put_bend(&mut k, XZ, XZ_SIGN, b);
        k
    }
}
