//! `flowmbd-belt`: belt-drive studies.
//!
//! Subcommands (one per study; `--help` on each lists its options):
//! - `demo`: rigid-body slider-crank driven at constant speed (integrator demonstration; the default
//!   until the flowing-material speed-loss study is complete).
//!
//! Run without a subcommand, the default study runs on its embedded defaults.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod ancf;
mod demo;

/// Belt-drive studies of the flowmbd toolkit.
#[derive(Debug, Parser)]
#[command(name = "flowmbd-belt", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    study: Option<Study>,
}

#[derive(Debug, Subcommand)]
enum Study {
    /// Rigid-body slider-crank with a rotational driver (mbd-core demonstration).
    Demo(demo::Args),
    /// Planar ANCF belt drive (Kerkkänen ch. 3).
    Ancf(ancf::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.study {
        Some(Study::Demo(args)) => demo::run(&args),
        Some(Study::Ancf(args)) => ancf::run(&args),
        None => demo::run(&demo::Args::default()),
    }
}
