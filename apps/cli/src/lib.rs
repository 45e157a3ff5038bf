//! # flowmbd-cli
//!
//! Shared plumbing for the `flowmbd-*` binaries (app conventions): TOML configuration with
//! embedded defaults, `--print-config`, `--config`, `--out`, `--json`, progress bars, CSV/plot/VTK
//! output folders and the exit-code policy (2 = bad input, 1 = numerical failure).
