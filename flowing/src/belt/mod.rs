//! The flowing-material belt drive (Ribaric ch. 5–6): a belt loop whose FE mesh stays in place
//! while the material flows through it, reduced to contact-node static modes plus truncated
//! free-node modes, on two rigid pulleys with penalty contact and tanh friction.
//!
//! - [`BeltDriveConfig`]: Table 6-1 parameters;
//! - [`BeltFe`], [`FlowingBasis`]: the loop, its matrices and the reduction basis (5.9)–(5.13);
//! - [`FlowingBelt`]: the flowing-material equations (5.14) as a [`mbd_core::SecondOrderSystem`];
//! - [`Schedule`]: the driver-speed and load-torque histories the models carry.
//!
//! The speed-loss procedure, Bechtel's line (6.3) and the `DriveModel` implementations of these
//! models live in the `drives` crate.

pub mod config;
pub mod contact;
pub mod flowing_system;
pub mod model;
pub mod nodal;
pub mod schedule;
mod statics;
pub mod wave;

pub use config::BeltDriveConfig;
pub use flowing_system::{ArmModel, FlowingBelt, NodeReport, PulleyMotion};
pub use model::{BeltFe, FlowingBasis};
pub use schedule::{Harmonic, Schedule, Signal};
