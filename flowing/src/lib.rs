//! # flowing
//!
//! The Eulerian flowing-material layer (Ribaric 2012 ch. 4–8 and App. A): mode-shape derivative
//! operators along a flow coordinate, the travelling string and the flowing-material belt drive.
//! The reduced FE tire, whose mesh does not move with the material either, is the `tire` crate
//! built on these operators.
//!
//! * [`grid`], [`derivative`]: nodal values sampled at flow coordinates `s_i` (open or closed),
//!   finite-difference, FE-consistent, polynomial and spectral derivative operators, applied per
//!   DOF component (Ribaric App. A).
//! * [`galerkin`], [`gyroscopic`]: the analytical moving string (4.26)–(4.30), state-matrix
//!   eigenvalues and the matrix-exponential response.
//! * [`travelling`]: the travelling string with fixed ends in flowing-material modal coordinates
//!   (4.12)–(4.20), a gyroscopic [`mbd_core::SecondOrderSystem`].
//! * [`string_study`], [`string_sweep`], [`string_simulate`]: the string's modes study, speed
//!   sweep and pluck transient (configuration,
//!   checks, summaries), shared by `flowmbd-string` and the Python package.
//! * [`contact`], [`pulley`]: the string wrapped on two pulleys with variable-size contact
//!   (4.10), (4.11) and the travelling string with variable contact (4.31)–(4.40).

// Dense numerical kernels index several arrays with one loop variable; iterator chains would
// obscure the equations.
#![allow(clippy::needless_range_loop)]

pub mod belt;
pub mod contact;
pub mod derivative;
pub mod error;
pub mod galerkin;
pub mod grid;
pub mod gyroscopic;
pub mod modal;
pub mod params;
pub mod pulley;
pub mod spectrum;
pub mod string_fe;
pub mod string_simulate;
pub mod string_study;
pub mod string_sweep;
pub mod string_wrap;
pub mod travelling;

pub use contact::{ContactConfig, ContactString, HarmonicLoad, simulate_contact};
pub use derivative::{
    DerivativeMethod, FlowLine, LineOperator, ModeDerivatives, mode_shape_derivatives,
};
pub use error::FlowError;
pub use galerkin::GalerkinString;
pub use grid::{End, FlowGrid, Topology};
pub use gyroscopic::{GyroscopicSystem, StateEigen};
pub use modal::ModalBasis;
pub use params::StringConfig;
pub use pulley::PulleyObstacle;
pub use string_fe::StringMesh;
pub use travelling::{AxialMotion, FlowingString, TimeHistory, simulate_rk4, triangular_pluck};
