//! # mbd-core
//!
//! Constrained multibody dynamics for flowmbd: Euler-parameter kinematics, rigid bodies and the
//! Newton–Euler equations, joints and rheonomic drivers, force elements, the augmented
//! (index-1) equations of motion (Ribaric (2.16), Lin (2.27)), the generic
//! [`system::SecondOrderSystem`] interface that every model of the workspace implements, and the
//! time integrators (RK4, Dormand–Prince 5(4) with events, generalized-α in index-3 form).
//!
//! ## Modules
//!
//! * [`kinematics`]: Euler parameters `A(p)`, `G(p)`, `L(p)`, `ṗ`/`ω` relations, `p̈` (Lin
//!   (2.4)–(2.21)), tilde and stacking helpers, planar rotation matrices;
//! * [`body`]: rigid bodies, body states and kinematics;
//! * [`marker`]: markers, a point and a frame on a rigid body, the ground or a flexible node,
//!   and the kinematic terms of joint equations;
//! * [`constraints`]: the [`constraints::Constraint`] extension point and the joints
//!   (fixed, spherical, revolute, universal, prismatic, distance, point-on-plane, planar
//!   revolute) and rheonomic rotation and point drivers, written once against markers and
//!   used by [`MultibodySystem`] and [`floating::FloatingSystem`];
//! * [`forces`]: the [`forces::ForceElement`] extension point, gravity, spring-dampers,
//!   applied forces and torques;
//! * [`multibody`]: [`MultibodySystem`], which implements [`SecondOrderSystem`];
//! * [`integrators`]: [`Rk4`], [`DormandPrince`] (error control, dense output, events),
//!   [`GeneralizedAlpha`] (index 3, Newton, dense/sparse LU), index-1 accelerations and
//!   reactions, projections;
//! * [`newton`]: the one Newton–Raphson solver (line search, load stepping, active-set passes,
//!   report) behind every static solve of the workspace, extension point [`newton::NewtonProblem`];
//! * [`workspace`]: [`Workspace`], the caller-owned scratch of a model's hot methods;
//! * [`parallel`]: matrix–vector products split between two threads ([`parallel::SplitProduct`]);
//! * [`linalg`]: the augmented (KKT) solver; [`statics`]: static equilibrium;
//!   [`history`]: CSV time histories;
//! * [`input`]: the one bounded reader of input files ([`input::read_bounded`],
//!   [`input::read_text`], [`input::InputError`]) and writer ([`output::write_atomic`]);
//! * [`config`]: partial configurations read deeply over the defaults ([`config::from_partial`]);
//! * [`validate`]: the one validation shape ([`Validate`], [`InvalidField`] with the field path)
//!   and the shared range checks.
//!
//! ## Example: a pendulum on a revolute joint
//!
//! ```
//! use mbd_core::constraints::Revolute;
//! use mbd_core::marker::Marker;
//! use mbd_core::forces::Gravity;
//! use mbd_core::integrators::{AlphaConfig, GeneralizedAlpha};
//! use mbd_core::{BodyState, MultibodySystem, RigidBody};
//! use nalgebra::{Vector3, Vector4};
//!
//! let mut sys = MultibodySystem::new();
//! let bar = sys.add_body(RigidBody::with_principal("bar", 1.0, [1e-3, 0.083, 0.083])?);
//! sys.add_constraint(Revolute {
//!     name: "hinge".into(),
//!     i: Marker::new(None, Vector3::zeros(), Vector3::z()),
//!     j: Marker::new(Some(bar), Vector3::new(-0.5, 0.0, 0.0), Vector3::z()),
//! })?;
//! sys.add_force(Gravity { g: Vector3::new(0.0, -9.81, 0.0) })?;
//! let p = Vector4::new(1.0, 0.0, 0.0, 0.0);
//! let s0 = sys.state(0.0, &[BodyState::at_rest(Vector3::new(0.5, 0.0, 0.0), p)])?;
//! let alpha = GeneralizedAlpha::new(AlphaConfig { h: 1e-3, rho_inf: 0.8, ..Default::default() });
//! let sol = alpha.integrate(&sys, s0, 0.5, |_| {})?;
//! // the hinge keeps the bar end at the origin; energy is nearly conserved
//! let r = Vector3::new(sol.state.q[0], sol.state.q[1], sol.state.q[2]);
//! assert!((r.norm() - 0.5).abs() < 1e-9);
//! assert_eq!(sol.stats.steps, 500);
//! # Ok::<(), mbd_core::MbdError>(())
//! ```

#![allow(clippy::needless_range_loop, clippy::too_many_arguments)]

pub mod config;
pub mod error;
mod forward;
pub mod input;
pub mod integrators;
pub mod linalg;
pub mod output;
pub mod system;
pub mod validate;
pub mod workspace;

pub use error::MbdError;
pub use integrators::{
    AlphaConfig, DormandPrince, GeneralizedAlpha, Integrator, Observer, Recorder, Rk4, Solution,
    State, Stats, StepCorrection, Stepper,
};
pub use system::{ForceTangent, SecondOrderSystem, SysMatrix, central_difference_column};
pub use validate::{InvalidField, Validate};
pub use workspace::Workspace;
pub mod body;
pub mod composite;
pub mod constraints;
pub mod floating;
pub mod forces;
pub mod history;
pub mod kinematics;
pub mod least_squares;
pub mod marker;
pub mod multibody;
pub mod newton;
pub mod parallel;
pub mod roots;
pub mod simd;
pub mod statics;

pub use body::{BodyState, RigidBody};
pub use composite::{CompositeSystem, Coupling, CouplingEval};
pub use history::{History, Probe};
pub use multibody::MultibodySystem;
pub use statics::{StaticOptions, StaticSolution, static_equilibrium};
