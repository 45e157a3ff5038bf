//! # flowing
//!
//! The Eulerian flowing-material layer (Ribaric 2012 ch. 4–8 and App. A): mode-shape derivative
//! operators along a flow coordinate, the travelling string, the flowing-material belt drive and
//! the reduced FE tire whose mesh does not move with the material.
//!
//! * [`grid`], [`derivative`]: nodal values sampled at flow coordinates `s_i` (open or closed),
//!   finite-difference, FE-consistent, polynomial and spectral derivative operators, applied per
//!   DOF component (Ribaric App. A).

pub mod derivative;
pub mod error;
pub mod grid;

pub use derivative::{
    DerivativeMethod, FlowLine, LineOperator, ModeDerivatives, mode_shape_derivatives,
};
pub use error::FlowError;
pub use grid::{End, FlowGrid, Topology};
