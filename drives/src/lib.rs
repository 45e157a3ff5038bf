//! Belt-drive procedures and studies above the model crates: the speed-loss procedure of
//! Ribaric §6.4–6.5 and the FEAD sweep for any [`belt::BeltModel`], the ANCF belt on any
//! [`belt::Drive`], and the studies the `flowmbd-belt` app and the Python package call.
//!
//! * [`study`]: the model kinds ([`ModelKind`]) and their settings, any model built for a
//!   drive ([`study::AnyModel`]), the speed-loss study per driver speed;
//! * [`speed_loss`]: the procedure ([`speed_loss_sweep`]);
//! * [`speed_loss_study`]: the study's configuration and summary (shared by the app and the
//!   Python package);
//! * [`fead`]: the front-end accessory drive study over an engine-speed sweep;
//! * [`crank_trace`]: a measured crankshaft speed trace from a CSV file (the FEAD's input);
//! * [`fead_design`]: the FEAD's steady design without time stepping (span tensions, arm,
//!   slip arcs, hub loads, slip margins), its modes and Campbell diagram (issue 36);
//! * [`ancf_model`]: the ANCF belt (Kerkkänen ch. 3) on any drive, a [`belt::BeltModel`];
//! * [`analytical`]: Bechtel's line (6.3) and the Euler–Eytelwein capacity;
//! * [`bechtel_steady`]: Bechtel's steady belt-drive model with belt inertia (Kerkkänen §4.1);
//! * [`ancf_run`], [`ancf_study`]: the ANCF belt-drive study of Kerkkänen ch. 3 (time loop with
//!   sampled outputs, closure);
//! * [`plate_study`]: the three-dimensional plate-belt study of Kerkkänen §4.6;
//! * [`ringdown`]: a drive's free ring-down after a torque pulse and its spectral peaks (the
//!   design study's modes against the time simulation);
//! * [`wave`]: the measurements of the rotating vs non-rotating belt demonstration (Fig. 6-3);
//! * [`table_6_1`]: Ribaric's Table 6-1 drive, the default of the speed-loss study.
//!
//! Layering: `drives` depends on `belt`, `flowing`, `ancf`, `contact`, `fe-model` and
//! `mbd-core`; nothing below depends on it.

pub mod analytical;
pub mod ancf_model;
pub mod ancf_run;
pub mod ancf_study;
pub mod bechtel_steady;
pub mod crank_trace;
pub mod error;
pub mod fead;
pub mod fead_design;
pub mod plate_study;
pub mod ringdown;
pub mod simulation;
pub mod speed_loss;
pub mod speed_loss_study;
pub mod study;
pub mod table_6_1;
pub mod wave;

pub use analytical::{
    PenetratingString, analytical_speed_loss, bechtel, euler_eytelwein_capacity,
    penetrating_string, penetrating_string_capacity,
};
/// The belt drive's vocabulary (re-exported: one crate's API builds and runs any drive).
pub use belt;
pub use error::DriveError;
pub use simulation::{AnySimulation, BeltSimulation, DriveSimulationConfig, SimulationBuildError};
pub use speed_loss::{BeltData, SpeedLossConfig, SpeedLossPoint, speed_loss_sweep};
pub use speed_loss_study::{SpeedLossStudyConfig, SpeedLossSummary};
pub use study::{AnyModel, ModelKind, ModelSettings, NodalConfig, SpeedLossCase};
