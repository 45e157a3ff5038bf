//! Beam cross-sections described by their even area moments, and the exact three-point rule
//! over the section height that they define.

use crate::error::{AncfError, check_positive};
use serde::{Deserialize, Serialize};

/// A doubly symmetric cross-section, described by the moments that enter the ANCF energies
/// (Kerkkänen §2.2.1): `A = ∫dA` \[m²\], `I₂ = ∫y² dA` \[m⁴\], `I₄ = ∫y⁴ dA` \[m⁶\]; `y` is the
/// in-plane transverse coordinate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct Section {
    /// Area `A` \[m²\].
    pub area: f64,
    /// Second moment `I₂ = ∫y² dA` \[m⁴\].
    pub i2: f64,
    /// Fourth moment `I₄ = ∫y⁴ dA` \[m⁶\].
    pub i4: f64,
    /// Height in `y` \[m\] (used only for output and contact offsets).
    pub height: f64,
}

impl Section {
    /// Rectangle of width `w` (out of plane) and height `h` (in plane, along `y`) \[m\]:
    /// `A = wh`, `I₂ = wh³/12`, `I₄ = wh⁵/80`.
    pub fn rectangle(width: f64, height: f64) -> Result<Self, AncfError> {
        check_positive("section: width", width, " m")?;
        check_positive("section: height", height, " m")?;
        Ok(Self {
            area: width * height,
            i2: width * height.powi(3) / 12.0,
            i4: width * height.powi(5) / 80.0,
            height,
        })
    }

    /// The three-point rule `(yₖ, wₖ)` over the section that integrates `∫ p(y) dA` exactly
    /// for every polynomial `p` of degree ≤ 5: points `0, ±√(I₄/I₂)`, weights
    /// `A − I₂²/I₄` and `I₂²/(2I₄)` (the moment-matching rule; for a rectangle it is the
    /// 3-point Gauss rule times the width). The ANCF strain energies are polynomials of
    /// degree ≤ 4 in `y`, so this is the "closed-form integration over the cross-section"
    /// of Kerkkänen §2.2.1.
    pub fn y_rule(&self) -> [(f64, f64); 3] {
        let y1 = (self.i4 / self.i2).sqrt();
        let w1 = self.i2 * self.i2 / (2.0 * self.i4);
        [(-y1, w1), (0.0, self.area - 2.0 * w1), (y1, w1)]
    }
}
