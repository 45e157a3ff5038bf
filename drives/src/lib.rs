//! Belt drives above the model crates: the speed-loss procedure of Ribaric §6.4–6.5 for any
//! belt model, the models that run it, and the drive studies the `flowmbd-belt` app calls.
//!
//! * [`DriveModel`]: what the procedure needs from a model, implemented here for the flowing
//!   crate's flowing-material ([`flowing::belt::FlowingBelt`], Ribaric (5.14)) and nodal
//!   ([`flowing::belt::nodal::NodalBelt`], (5.7)) belts, and for the ANCF belt through
//!   [`ancf_drive_model::AncfDrive`];
//! * [`Schedule`]: the smooth driver-speed and load-torque histories (defined in
//!   `flowing::belt`, whose models carry them; re-exported here);
//! * [`speed_loss`]: the procedure ([`speed_loss_sweep`]);
//! * [`analytical`]: Bechtel's line (6.3) and the Euler–Eytelwein capacity;
//! * [`report`]: span tensions, wrap distributions, adhesion and slip arcs, hub loads and
//!   torques of a drive state, for any model and any number of pulleys;
//! * [`bechtel_steady`]: Bechtel's steady belt-drive model with belt inertia (Kerkkänen §4.1):
//!   tension, speed, friction and normal force along the belt, full and capstan forms;
//! * [`ancf_drive_model`]: the Table 6-1 → ANCF adapter (Kerkkänen ch. 3 elements on Ribaric's
//!   drive);
//! * [`study`]: the speed-loss study per model and driver speed;
//! * [`speed_loss_study`]: the study's configuration and summary (shared by the app and the
//!   Python package);
//! * [`ancf_run`]: the ANCF belt drive's time loop with sampled outputs, and its closure;
//! * [`ancf_study`]: the ANCF belt-drive study's configuration, summary and runs (shared by the
//!   app and the Python package);
//! * [`plate_study`]: the three-dimensional plate-belt study of Kerkkänen §4.6 (Models 1 and 2)
//!   with the comparison against [`bechtel_steady`];
//! * [`wave`]: the measurements of the rotating vs non-rotating belt demonstration (Fig. 6-3).
//!
//! Layering: `drives` depends on `flowing`, `ancf`, `fe-model` and `mbd-core`; nothing below
//! depends on it (flowing and ancf are siblings, the adapter between them lives here).

pub mod analytical;
pub mod ancf_drive_model;
pub mod ancf_layout;
pub mod ancf_run;
pub mod ancf_study;
pub mod bechtel_steady;
pub mod error;
pub mod fead;
pub mod layout;
pub mod model;
pub mod plate_study;
pub mod report;
pub mod speed_loss;
pub mod speed_loss_study;
pub mod study;
pub mod wave;

pub use analytical::{
    PenetratingString, analytical_speed_loss, bechtel, euler_eytelwein_capacity,
    penetrating_string, penetrating_string_capacity,
};
pub use error::DriveError;
pub use flowing::belt::Schedule;
pub use model::{BeltData, DriveModel};
pub use report::{DriveReport, DriveSnapshot, PulleyRole};
pub use speed_loss::{SpeedLossConfig, SpeedLossPoint, speed_loss_sweep};
pub use speed_loss_study::{SpeedLossStudyConfig, SpeedLossSummary};
pub use study::{ModelKind, NodalConfig, SpeedLossCase, SpeedLossModel};
