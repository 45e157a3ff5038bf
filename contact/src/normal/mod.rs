//! Normal contact laws (penalty): force as a function of penetration `d ≥ 0` and its rate,
//! with derivatives for implicit integration; [`NormalSpec`] maps configuration tables to them.

use serde::{Deserialize, Serialize};

pub mod spec;

pub use spec::NormalSpec;

/// Normal force and its partial derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NormalForce {
    /// Force (per unit length for distributed laws) \[N or N/m\]; positive pushes apart.
    pub force: f64,
    /// `∂force/∂d`.
    pub d_pen: f64,
    /// `∂force/∂ḋ`.
    pub d_rate: f64,
}

/// A penalty law `f_n(d, ḋ)`; it is only evaluated for `d ≥ 0` (open contacts carry no force).
pub trait NormalLaw {
    /// Force and derivatives at penetration `d` \[m\] and penetration rate `ḋ` \[m/s\].
    fn normal(&self, pen: f64, pen_rate: f64) -> NormalForce;

    /// The forces of a batch of points (structure of arrays, force-only evaluations):
    /// `out[q] = f_n(pen[q], pen_rate[q])` for every `q` of `out`. The default calls
    /// [`NormalLaw::normal`] point by point; a law may override it with a loop that the
    /// compiler vectorises (the same operations per point, so the same values).
    #[inline(always)]
    fn normal_forces(&self, pen: &[f64], pen_rate: &[f64], out: &mut [f64]) {
        for (q, o) in out.iter_mut().enumerate() {
            *o = self.normal(pen[q], pen_rate[q]).force;
        }
    }
}

/// Linear penalty with damping, Kerkkänen (3.20): `f_n = k_p d + c_p ḋ` (per unit length:
/// `k_p` \[N/m²\], `c_p` \[N·s/m²\]). Not clipped: the damping term may make it negative at the
/// exit of a contact arc, as in the thesis (seed note §4.2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct LinearPenalty {
    /// Stiffness `k_p`.
    pub stiffness: f64,
    /// Damping `c_p`.
    pub damping: f64,
}

impl NormalLaw for LinearPenalty {
    fn normal(&self, pen: f64, pen_rate: f64) -> NormalForce {
        NormalForce {
            force: self.stiffness * pen + self.damping * pen_rate,
            d_pen: self.stiffness,
            d_rate: self.damping,
        }
    }
}

/// Polynomial penalty of Ribaric (6.1), scaled by the tributary length `L_ele` of the contact
/// node: `F_N = k₂ L δ² + k₁ L δ` (Ribaric: `k₂ = 3025.6·10⁸ N/m³`, `k₁ = 6.5·10⁷ N/m²`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct PolynomialPenalty {
    /// Quadratic coefficient `k₂` \[N/m³ per metre of belt\].
    pub quadratic: f64,
    /// Linear coefficient `k₁` \[N/m² per metre of belt\].
    pub linear: f64,
    /// Tributary length `L_ele` \[m\].
    pub length: f64,
}

impl PolynomialPenalty {
    /// Ribaric's belt values (6.1) for a node representing `length` metres of belt.
    pub fn ribaric(length: f64) -> Self {
        Self {
            quadratic: 3025.6e8,
            linear: 6.5e7,
            length,
        }
    }
}

impl NormalLaw for PolynomialPenalty {
    fn normal(&self, pen: f64, _pen_rate: f64) -> NormalForce {
        NormalForce {
            force: self.length * (self.quadratic * pen * pen + self.linear * pen),
            d_pen: self.length * (2.0 * self.quadratic * pen + self.linear),
            d_rate: 0.0,
        }
    }
}
