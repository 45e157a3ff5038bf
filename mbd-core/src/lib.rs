//! # mbd-core
//!
//! Constrained multibody dynamics for flowmbd: Euler-parameter kinematics, rigid bodies and the
//! Newton–Euler equations, joints and rheonomic drivers, force elements, the augmented
//! (index-1) equations of motion (Ribaric (2.16), Lin (2.27)), the generic
//! [`system::SecondOrderSystem`] interface that every model of the workspace implements, and the
//! time integrators (RK4, Dormand–Prince 5(4) with events, generalized-α in index-3 form).
//!
//! ## Using the integrators
//!
//! ```ignore
//! use mbd_core::integrators::{AlphaParams, GeneralizedAlpha, State};
//! let alpha = GeneralizedAlpha::new(AlphaParams { h: 1e-3, rho_inf: 0.8, ..Default::default() });
//! let sol = alpha.integrate(&model, State::new(0.0, q0, v0), 1.0, |s| println!("{}", s.t))?;
//! println!("{:?}", sol.stats);
//! ```

#![allow(clippy::needless_range_loop, clippy::too_many_arguments)]

pub mod error;
pub mod integrators;
pub mod linalg;
pub mod system;

pub use error::MbdError;
pub use integrators::{
    AlphaParams, DormandPrince, GeneralizedAlpha, Integrator, Rk4, Solution, State, Stats,
};
pub use system::{ForceTangent, SecondOrderSystem, SysMatrix};
pub mod body;
pub mod constraints;
pub mod examples_chain;
pub mod floating;
pub mod forces;
pub mod history;
pub mod kinematics;
pub mod multibody;
pub mod statics;

pub use body::{BodyState, RigidBody};
pub use history::{History, Probe};
pub use multibody::MultibodySystem;
pub use statics::{StaticOptions, StaticSolution, static_equilibrium};
