//! The package's integration tests, one module per file, in one test binary (one link
//! instead of one per file: the CI build time, `.ci/run`). Run one file's tests with
//! `cargo test --release -p <package> --test integration <module>::`.

mod cache;
mod centre_motion;
mod cli;
mod common;
mod config_mutation;
mod fmu;
mod hardening;
mod import_checks;
mod import_errors;
