//! # belt — the belt drive's vocabulary
//!
//! One home for what every belt model and study speaks, below the models (`flowing`, `ancf`)
//! and above the engine (`mbd-core`, `contact`):
//!
//! * [`Signal`] — every prescribed history (a pulley's speed, a load torque): constant,
//!   Kerkkänen's ramps (3.29), (3.30), Ribaric's smooth schedules, measured traces, plus
//!   harmonics (engine orders);
//! * [`Motion`] — how a pulley turns: speed-driven, loaded, idler (with a viscous damper);
//!   a loaded pulley optionally behind a [`Decoupler`] (spring, damper, one-way clutch);
//! * [`Pulley`] — the one pulley type (centre, belt-line radius, wrap side, motion; crown,
//!   flanges and centre shift for spatial models);
//! * [`BeltPath`] — the open belt's path over the pulleys (spans and wraps, Ribaric
//!   (5.1)–(5.4));
//! * [`Tensioner`] — a pivoted arm with spring, damper and dry friction;
//! * [`Section`], [`MaterialLaw`], [`BeltContact`], [`BeltDamping`] — the belt;
//! * [`Layout`] → [`Drive`] — a drive as written, checked and resolved once (mounting
//!   tension, belt length, tensioner arm angle, wraps);
//! * [`BeltModel`] — the one public trait every belt model implements in its own crate;
//! * [`Report`] — the one report (span forces, wraps, slip arcs, hub loads, torque and power
//!   balances), computed from any [`BeltModel`]'s [`Snapshot`].
//!
//! SI units throughout; speeds and torques of pulleys in the belt's travel sense.

pub mod coordinates;
pub mod decoupler;
pub mod layout;
pub mod model;
pub mod motion;
pub mod path;
pub mod pulley;
pub mod report;
pub mod section;
pub mod signal;
pub mod tensioner;

pub use coordinates::{HasMotion, PulleyCoordinates};
pub use decoupler::{ClutchState, Decoupler, DecouplerForces, DecouplerState};
pub use layout::{
    Arm, Drive, Layout, MAX_MOUNTING_STRAIN, MAX_PULLEYS, MIN_WRAP_DEG, PARTIAL_RULES,
};
pub use model::{BeltModel, ModelTraits, PulleyState, Snapshot, SpanState, WrapPoint};
pub use motion::{Motion, Role};
pub use path::{
    BeltPath, LineOfAction, PathPiece, PathPoint, Segment, SpanLine, tributary_lengths,
};
pub use pulley::{CentreShift, Pulley, WrapSide};
pub use report::{BALANCE_TOLERANCE, Balances, HubLoad, PulleyReport, Report, SpanReport};
pub use section::{BeltContact, BeltDamping, MaterialLaw, Ribs, Section};
pub use signal::{Harmonic, Shape, Signal};
pub use tensioner::Tensioner;
