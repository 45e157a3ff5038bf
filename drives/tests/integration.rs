//! The package's integration tests, one module per file, in one test binary (one link
//! instead of one per file: the CI build time, `.ci/run`). Run one file's tests with
//! `cargo test --release -p <package> --test integration <module>::`.

mod ancf_layout;
mod common;
mod crank_trace;
mod fead_design;
mod fead_meaning;
mod fead_steady_means;
mod fead_step;
mod fead_sweep;
mod flowing_creep;
mod flowing_span_force;
mod friction_default;
mod issue35_inputs;
mod layout;
mod layout_nodal;
mod partial_rules;
mod ribs;
mod runaway_mean;
mod simulation;
