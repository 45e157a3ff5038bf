//! Linear elastic material data and the constitutive matrices of the ANCF strain energies.

use crate::error::{AncfError, invalid};
use serde::{Deserialize, Serialize};

/// Isotropic material: Young's modulus `E` \[Pa\], Poisson's ratio `ν` \[-\], density `ρ` \[kg/m³\],
/// shear correction factor `k_s` \[-\] (5/6 in all of Kerkkänen's chapter-2 examples).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Material {
    /// Young's modulus `E` \[Pa\].
    pub young: f64,
    /// Poisson's ratio `ν` \[-\].
    pub poisson: f64,
    /// Density `ρ` \[kg/m³\].
    pub density: f64,
    /// Shear correction factor `k_s` \[-\].
    pub shear_factor: f64,
}

impl Material {
    /// Validated material with `k_s = 5/6`.
    pub fn new(young: f64, poisson: f64, density: f64) -> Result<Self, AncfError> {
        let m = Self {
            young,
            poisson,
            density,
            shear_factor: 5.0 / 6.0,
        };
        m.validate()?;
        Ok(m)
    }

    /// Check the ranges: `E > 0`, `−1 < ν < ½`, `ρ ≥ 0`, `k_s > 0`.
    pub fn validate(&self) -> Result<(), AncfError> {
        if !(self.young.is_finite() && self.young > 0.0) {
            return Err(invalid(
                "material: young",
                format!("E must be > 0 Pa, got {}", self.young),
            ));
        }
        if !(self.poisson.is_finite() && self.poisson > -1.0 && self.poisson < 0.5) {
            return Err(invalid(
                "material: poisson",
                format!("ν must lie in (-1, 0.5), got {}", self.poisson),
            ));
        }
        if !(self.density.is_finite() && self.density >= 0.0) {
            return Err(invalid(
                "material: density",
                format!("ρ must be ≥ 0 kg/m³, got {}", self.density),
            ));
        }
        if !(self.shear_factor.is_finite() && self.shear_factor > 0.0) {
            return Err(invalid(
                "material: shear_factor",
                format!("k_s must be > 0, got {}", self.shear_factor),
            ));
        }
        Ok(())
    }

    /// Shear modulus `G = E / (2(1 + ν))` \[Pa\].
    pub fn shear_modulus(&self) -> f64 {
        self.young / (2.0 * (1.0 + self.poisson))
    }

    /// Lamé constants `(λ, μ)` \[Pa\], Kerkkänen (2.17).
    pub fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.young, self.poisson);
        (
            e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)),
            e / (2.0 * (1.0 + nu)),
        )
    }

    /// Constitutive matrix of the full plane-strain continuum energy, Kerkkänen (2.16)–(2.17),
    /// acting on `ε = [ε_xx, ε_yy, 2ε_xy]`: `[[λ+2μ, λ, 0], [λ, λ+2μ, 0], [0, 0, μ]]`.
    pub fn continuum_matrix(&self) -> [[f64; 3]; 3] {
        let (l, m) = self.lame();
        [[l + 2.0 * m, l, 0.0], [l, l + 2.0 * m, 0.0], [0.0, 0.0, m]]
    }

    /// Constitutive matrix of the Poisson-free energy, Kerkkänen (2.18)–(2.19):
    /// `U = ½∫(E ε_xx² + E ε_yy² + 4 k_s G ε_xy²) dV` ⇒ `diag(E, E, k_s G)` on `[ε_xx, ε_yy, 2ε_xy]`.
    pub fn poisson_free_matrix(&self) -> [[f64; 3]; 3] {
        let g = self.shear_factor * self.shear_modulus();
        [
            [self.young, 0.0, 0.0],
            [0.0, self.young, 0.0],
            [0.0, 0.0, g],
        ]
    }
}
