//! The package's integration tests, one module per file, in one test binary (one link
//! instead of one per file: the CI build time, `.ci/run`). Run one file's tests with
//! `cargo test --release -p <package> --test integration <module>::`.

mod active_set;
mod common;
mod composite;
mod constraint_consistency;
mod correction_limit;
mod euler_props;
mod flex_joints;
mod frozen_matrix;
mod integrators_basic;
mod kkt_solver;
mod limits;
mod rigid_validation;
mod statics_history;
mod stepper;
mod stiff_chain;
mod support;
