//! Floating-frame deformable bodies in a multibody system (Lin 2005 ch. 3–5 and 8; Ribaric
//! 2012 §2.2).
//!
//! A [`FlexBody`] has a body frame `(r, A(p))` and local nodal deflections `δ' = Ψ' z`
//! (Lin (5.12)): the **nodal** formulation is `Ψ' = I` (or the nodal-fixed selection
//! `[0; I]` of Lin (4.2)), the **modal** formulation any reduction basis (built by the
//! `reduction` crate and handed down as plain data). The frame is fixed by an
//! [`AxisCondition`]: nodal-fixed anchors (the anchored coordinates are simply absent from
//! `Ψ'`, Lin §5.4.1), mean axes (Lin Table 4-2, Lagrange multipliers), principal axes
//! (Ribaric (2.42)–(2.44)), or a rigid body sharing the frame ([`RigidCore`], Ribaric
//! (2.45)–(2.52)).
//!
//! [`FloatingSystem`] couples flexible bodies, rigid bodies (mbd-core's [`crate::RigidBody`]),
//! the joints and drivers of [`crate::constraints`] between markers ([`crate::marker::Marker`]:
//! ground, rigid-body frame or flexible node, Lin (2.22)–(2.24), (5.1)–(5.7)), prescribed point
//! motions ([`crate::constraints::PointDriver`], Lin (7.7)–(7.9)), gravity and point loads, and
//! implements [`crate::SecondOrderSystem`] so that mbd-core's integrators run it.
//!
//! Velocity coordinates per body are `(ṙ, ω', ż)` with the **body-frame** angular velocity
//! `ω'` (as for mbd-core's rigid bodies), so that the equations are Lin (3.36)/(5.19) written
//! in local components (Kane's form `Lᵀ(f − M d̈) = 0` with `d̈ = L v̇ + A w'`).

mod body;
mod system;

pub use body::{AxisCondition, ElasticForces, FlexBody, RigidCore};
pub use system::{FlexState, FloatingSystem, NodeLoad};
