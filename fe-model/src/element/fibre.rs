//! Smeared uniaxial fibre reinforcement of a continuum element (like ABAQUS `*REBAR`).
//!
//! A fibre family is a unit direction `a` and a smeared modulus `E_f φ` \[Pa\] (fibre Young's
//! modulus times the fibre volume fraction φ). The fibres carry only their own axial strain
//! `ε_aa = a·ε·a`, so the family adds the rank-one elasticity
//! `D_f = E_f φ · m mᵀ` with the Voigt vector (engineering shears γxy, γyz, γzx)
//! `m = (a_x², a_y², a_z², a_x a_y, a_y a_z, a_z a_x)` (`ε_aa = mᵀ ε`, `σ_f = E_f φ ε_aa a⊗a`),
//! integrated as `K_f = ∫ Bᵀ D_f B dV` on top of the matrix material (the small-strain form of
//! the smeared rebar layer of the ABAQUS Analysis User's Manual, `*REBAR`; derived here from the
//! fibre strain energy `½ E_f φ ε_aa²` per unit volume). The fibre density enters the mass as
//! `ρ_f φ` \[kg/m³\].
//! Compressive fibre buckling and the fibre-rubber slip are not modelled (linear, tension and
//! compression alike), which is adequate for the small vibrations of a prestressed tire.

use crate::FeError;
use serde::{Deserialize, Serialize};

/// One uniaxial fibre family smeared over an element.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Fibre {
    /// Fibre direction `a` (unit vector in global axes, \[-\]).
    pub direction: [f64; 3],
    /// Smeared modulus `E_f φ` \[Pa\] (fibre Young's modulus × volume fraction).
    pub modulus: f64,
    /// Smeared density `ρ_f φ` \[kg/m³\] added to the matrix density (0 = massless fibres).
    pub density: f64,
}

impl Fibre {
    /// New fibre family; `direction` is normalised (it must be finite and non-zero),
    /// `modulus` and `density` must be finite and ≥ 0.
    pub fn new(direction: [f64; 3], modulus: f64, density: f64) -> Result<Self, FeError> {
        let n = direction.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(n.is_finite() && n > 0.0) {
            return Err(FeError::param(
                "fibre direction length",
                n,
                "must be finite and > 0",
            ));
        }
        let f = Self {
            direction: direction.map(|v| v / n),
            modulus,
            density,
        };
        f.validate()?;
        Ok(f)
    }

    /// Check that the direction is a unit vector (to 1e-9) and the modulus and density are
    /// finite and ≥ 0; the error names the field.
    pub fn validate(&self) -> Result<(), FeError> {
        let n = self.direction.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(n.is_finite() && (n - 1.0).abs() <= 1e-9) {
            return Err(FeError::param(
                "fibre direction length",
                n,
                "must be 1 (unit vector)",
            ));
        }
        FeError::check_non_negative("fibre modulus", self.modulus)?;
        FeError::check_non_negative("fibre density", self.density)?;
        Ok(())
    }

    /// Voigt vector `m` with `ε_aa = mᵀ ε` for engineering shear strains
    /// (order xx, yy, zz, γxy, γyz, γzx, as the hexahedron's B matrix).
    pub fn voigt(&self) -> [f64; 6] {
        let [x, y, z] = self.direction;
        [x * x, y * y, z * z, x * y, y * z, z * x]
    }
}
