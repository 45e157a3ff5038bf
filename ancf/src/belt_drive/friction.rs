//! The contact laws of the belt–pulley contact: the friction law is any law of the contact
//! crate chosen at run time ([`BeltFriction`] = [`contact::FrictionSpec`]: Kerkkänen's tri-linear
//! creep-rate law (Fig. 3.3), the Coulomb–tanh law (Ribaric (6.2)), Stribeck, …), the normal law
//! is [`BeltNormal`].

use contact::{NormalForce, NormalLaw};

/// Friction law per unit belt length: a `{ law = "creep_rate", mu, creep }` or
/// `{ law = "tanh", mu, kappa }` (or any other [`contact::FrictionSpec`]) table.
pub use contact::FrictionSpec as BeltFriction;

/// Normal law per unit belt length: `f_n = k₂ d² + k_p d + c_p ḋ` — Kerkkänen's linear penalty
/// with damping (3.20) when `k₂ = 0`, Ribaric's polynomial penalty (6.1) (there per contact node,
/// here per unit length) when `k₂ > 0`. Not clipped (seed note §4.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeltNormal {
    /// Linear coefficient `k_p` \[N/m²\].
    pub stiffness: f64,
    /// Quadratic coefficient `k₂` \[N/m³\].
    pub quadratic: f64,
    /// Damping `c_p` \[N·s/m²\].
    pub damping: f64,
}

impl NormalLaw for BeltNormal {
    #[inline]
    fn normal(&self, pen: f64, pen_rate: f64) -> NormalForce {
        NormalForce {
            force: (self.quadratic * pen + self.stiffness) * pen + self.damping * pen_rate,
            d_pen: 2.0 * self.quadratic * pen + self.stiffness,
            d_rate: self.damping,
        }
    }
}
