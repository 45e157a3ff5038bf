//! Planar ANCF belt drives (Kerkkänen ch. 3): the whole belt meshed with belt elements
//! (Kerkkänen §3.1) in a Lagrangian closed loop travelling around any number of pulleys,
//! distributed penalty contact with creep-rate (or tanh) friction evaluated by Gauss quadrature
//! along the elements (Kerkkänen (3.20)–(3.27)), pulleys driven by a prescribed speed history
//! (3.29) or free with an inertia and a load torque (3.26)–(3.30), all in one
//! [`SecondOrderSystem`](mbd_core::SecondOrderSystem) with the analytic Jacobian so that
//! mbd-core's generalized-α integrator converges in few Newton iterations.
//!
//! * [`spec`]: plain-data description (defaults: Kerkkänen Table 3.1);
//! * [`model`]: [`BeltDrive`], the system (sparse pattern built once, allocation-free element
//!   and contact loops);
//! * [`initial`]: the pre-strained initial configuration by a static solve;
//! * [`mod@simulate`]: generalized-α and explicit RK4 runs;
//! * [`post`]: tension, span and contact post-processing;
//! * [`closure`]: example 3.3-A (free belt closing to a circle);
//! * [`belt_model`]: [`AncfBelt`], the ANCF belt on any resolved [`belt::Drive`], a
//!   [`belt::BeltModel`] (the mounting to the installation tension, the tensioner's static arm).

pub mod belt_model;
pub mod closure;
pub mod friction;
pub mod initial;
pub mod model;
pub mod post;
pub mod simulate;
pub mod spec;

pub use belt_model::{AncfBelt, AncfConfig, AncfMapping};
pub use closure::{ClosureResult, free_belt_closure};
pub use friction::BeltFriction;
pub use initial::{InitialOptions, InitialState};
pub use model::{
    BeltArm, BeltDrive, Planar, PointRecord, PulleyLoad, SECTION_CELLS, SectionForces, SpanSection,
};
pub use simulate::{
    ExplicitStepLimit, IntegratorKind, SimulationConfig, VTOL_PER_TRANSITION_WIDTH, simulate,
};
pub use spec::{BeltDriveSpec, BeltSpec, ContactSpec};
