//! Library part of the `flowmbd-belt` app: glue between sibling crates that the binary's studies
//! and the workspace's validation tests share.
//!
//! * [`ancf_drive_model`]: the ANCF belt drive (`ancf::belt_drive`) seen through the flowing
//!   crate's [`flowing::belt::DriveModel`] trait, so that the speed-loss procedure runs it
//!   unchanged (`flowmbd-belt speed-loss --model ancf`).

pub mod ancf_drive_model;
