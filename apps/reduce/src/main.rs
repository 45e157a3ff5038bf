//! `flowmbd-reduce`: model reduction studies (Lin 2005) and user reductions.
//!
//! Subcommands: `lin-beam` (Lin ch. 6, 7.1, 8.5 on the Appendix A beam), `reduce` (reduce user
//! Matrix Market matrices and write a reduced-model file).

use clap::{Parser, Subcommand};
use std::process::ExitCode;

mod lin_beam;

/// Model reduction for flexible multibody models.
#[derive(Parser, Debug)]
#[command(name = "flowmbd-reduce", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Lin ch. 6-8 on the Appendix A beam: frequencies, Guyan models, profile tests, mean axes.
    LinBeam(lin_beam::Args),
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::LinBeam(a) => lin_beam::run(a),
    }
}
