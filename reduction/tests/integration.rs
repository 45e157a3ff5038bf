//! The package's integration tests, one module per file, in one test binary (one link
//! instead of one per file: the CI build time, `.ci/run`). Run one file's tests with
//! `cargo test --release -p <package> --test integration <module>::`.

mod issue35;
mod lyapunov;
mod partition;
mod partitioned_cb;
