//! Feature unification of the workspace's shared dependencies (no code): see `Cargo.toml`.
