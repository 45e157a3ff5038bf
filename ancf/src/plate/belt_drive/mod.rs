//! Three-dimensional belt drives with a thin-plate belt (Kerkkänen ch. 4, §4.5–4.6): the whole
//! belt meshed with one row of ANCF thin-plate elements (§4.3) closed into a loop, rigid
//! cylindrical pulleys (optionally crowned or flanged, through the `contact` crate's spatial
//! geometry), distributed penalty contact with damping and the tri-linear creep-rate friction
//! evaluated at `points²` (81) quadrature points per element by
//! [`contact::element_contact`] ((4.43)–(4.45) with the laws (3.20), (3.23)), a driver
//! with a prescribed speed ramp (3.29) and optional centre shift (4.46), and free pulleys with
//! inertia and load torque ((3.26), (4.47)), all in one
//! [`SecondOrderSystem`](mbd_core::SecondOrderSystem) with the analytic Jacobian, run by
//! mbd-core's integrators.
//!
//! * [`spec`]: plain-data description (Models 1 and 2 of Table 4.1);
//! * [`model`]: [`PlateBeltDrive`], the system;
//! * [`initial`]: the initial configuration by a static solve;
//! * [`post`]: strain measures, tension, speed, span states, torques, VTK surface;
//! * [`belt_model`]: [`PlateBelt`], the plate belt on any resolved [`belt::Drive`] without a
//!   tensioner, a [`belt::BeltModel`].

pub mod belt_model;
pub mod initial;
pub mod model;
pub mod post;
pub mod spec;

pub use crate::mounted::InitialOptions;
pub use belt_model::{PlateBelt, PlateConfig, PlateMapping};
pub use initial::PlateInitialState;
pub use model::{Plate, PlateBeltDrive, PlateContactRecord, PulleySurface};
pub use spec::{DEFAULT_POINTS_ACROSS, PlateBeltSpec, PlateContactSpec, PlateDriveSpec};
