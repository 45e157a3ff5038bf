//! # contact
//!
//! Contact geometry (circles, drums with cleats, planes), normal laws (linear and polynomial
//! penalty, unilateral Lagrange constraints) and friction laws (Coulomb–tanh, creep-rate, Coulomb
//! slip) behind small traits, with distributed contact along elements by Gauss quadrature.

pub mod quadrature;

pub use quadrature::GaussRule;
