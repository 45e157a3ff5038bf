//! The contact laws of the belt–pulley contact, both from the contact crate and chosen at run
//! time: the friction law [`BeltFriction`] = [`contact::FrictionSpec`] (Kerkkänen's tri-linear
//! creep-rate law (Fig. 3.3), the Coulomb–tanh law (Ribaric (6.2)), Stribeck, …) and the normal
//! law [`BeltNormal`] = [`contact::NormalSpec`] (`f_n = k₂ d² + k_p d + c_p ḋ` per unit belt
//! length: Kerkkänen's linear penalty with damping (3.20) when `k₂ = 0`, Ribaric's polynomial
//! penalty (6.1) otherwise; not clipped, seed note §4.2), built from the `[contact]` keys by
//! [`super::ContactSpec::normal_law`].

/// Friction law per unit belt length: a `{ law = "creep_rate", mu, creep }` or
/// `{ law = "tanh", mu, kappa }` (or any other [`contact::FrictionSpec`]) table.
pub use contact::FrictionSpec as BeltFriction;

/// Normal law per unit belt length (see the module documentation).
pub use contact::NormalSpec as BeltNormal;
