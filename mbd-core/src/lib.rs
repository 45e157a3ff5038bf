//! # mbd-core
//!
//! Constrained multibody dynamics for flowmbd: Euler-parameter kinematics, rigid bodies and the
//! Newton–Euler equations, joints and rheonomic drivers, force elements, the augmented
//! (index-1) equations of motion (Ribaric (2.16), Lin (2.27)), the generic
//! [`system::SecondOrderSystem`] interface that every model of the workspace implements, and the
//! time integrators (RK4, Dormand–Prince 5(4) with events, generalized-α in index-3 form).

pub mod error;
pub mod system;

pub use error::MbdError;
pub use system::{SecondOrderSystem, SysMatrix};
