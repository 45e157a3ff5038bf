//! Building the tire FE model from fe-model's generated truck-tire carcass
//! ([`mod@fe_model::generate::tire`]), with the inflation prestress entering through the geometric
//! stiffness (Ribaric §8.1: M and K "under load and inflation").

use crate::error::TireError;
use crate::mesh::TireFe;
use fe_model::generate::{TireConfig, tire};

/// The full-size truck tire (295/80 R22.5, 38 psi): fe-model's default generator settings.
pub fn truck_tire_config() -> TireConfig {
    TireConfig::default()
}

/// A coarse version of the truck tire (same dimensions, materials and inflation) for quick
/// tests: `circumferential` elements around, `section` along the cross-section, one through the
/// thickness; the candidate patch covers ±`patch_deg` degrees.
pub fn coarse_tire_config(circumferential: usize, section: usize, patch_deg: f64) -> TireConfig {
    TireConfig {
        circumferential_divisions: circumferential,
        section_divisions: section,
        thickness_divisions: 1,
        bead_elements: 1,
        patch_half_angle_deg: patch_deg,
        ..TireConfig::default()
    }
}

/// Generate the tire and assemble its FE model (lumped mass; `K + K_G` of the inflation
/// prestress). The candidate contact nodes are the generator's `contact_patch` set.
pub fn generated_tire(cfg: &TireConfig) -> Result<TireFe, TireError> {
    let t = tire(cfg)?;
    TireFe::from_fe_model(
        &t.model,
        "rim",
        "contact_patch",
        cfg.inflation_pressure > 0.0,
    )
}
