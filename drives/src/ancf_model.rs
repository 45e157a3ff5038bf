//! The ANCF belt on any drive, a [`belt::BeltModel`]: defined in the model's own crate
//! ([`ancf::belt_drive::belt_model`]) and re-exported here for the procedures and studies.

pub use ancf::belt_drive::belt_model::*;
