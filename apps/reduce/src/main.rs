//! `flowmbd-reduce`: model-reduction studies of the flowmbd toolkit.
//!
//! Subcommands (one module each; `--help` on each lists its options):
//! - `modes`: lowest modes of `K φ = λ M φ` read from Matrix Market files;
//! - `tire-mesh`: the generated truck-tire carcass, its M and K as Matrix Market, mesh as VTK
//!   and node sets as JSON;
//! - `lin-beam`: Lin ch. 6, 7.1 and 8.5 on the Appendix A beam.

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod lin_beam;
mod modes;
mod tire_mesh;

/// Model-reduction studies of the flowmbd toolkit.
#[derive(Debug, Parser)]
#[command(name = "flowmbd-reduce", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    study: Study,
}

#[derive(Debug, Subcommand)]
enum Study {
    /// Lowest natural frequencies and modes of Matrix Market M and K.
    Modes(modes::Args),
    /// Generate the truck-tire carcass mesh and write M, K, mesh and node sets.
    TireMesh(tire_mesh::Args),
    /// Lin ch. 6-8 on the Appendix A beam: frequencies, Guyan models, profile tests, mean axes.
    LinBeam(lin_beam::Args),
}

fn main() -> ExitCode {
    match Cli::parse().study {
        Study::Modes(args) => modes::run(&args),
        Study::TireMesh(args) => tire_mesh::run(&args),
        Study::LinBeam(args) => lin_beam::run(args),
    }
}
