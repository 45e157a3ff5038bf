//! The package's integration tests, one module per file, in one test binary (one link
//! instead of one per file: the CI build time, `.ci/run`). Run one file's tests with
//! `cargo test --release -p <package> --test integration <module>::`.

mod abaqus_hardening;
mod dense_eigen_accuracy;
mod hex8_rebar;
mod issue35;
mod mtx_fast_read;
mod mtx_hardening;
mod partition;
mod plausibility;
mod shifted_merge;
#[cfg(feature = "sprs")]
mod sprs_conv;
mod vtk_polyline;
