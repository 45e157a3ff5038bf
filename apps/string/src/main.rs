//! `flowmbd-string`: the travelling string of Ribaric ch. 4 (flowing material, analytical
//! Galerkin model, variable-size contact on two pulleys).
//!
//! Studies: `modes`, `sweep`, `simulate`, `wrap` (see `--help` of each). Defaults reproduce
//! Ribaric Sec. 4.2.3: L = 1 m, ρ = 7850 kg/m³, A = 7.854e-5 m², T = 1000 N.

mod common;
mod modes;
mod simulate;
mod sweep;
mod wrap;

use clap::{Parser, Subcommand};
use flowmbd_cli::run_study;
use std::process::ExitCode;

/// The app's name (`flowmbd-string`: its default output folder `out/string/<study>`).
const APP: &str = "string";

#[derive(Parser, Debug)]
#[command(
    name = "flowmbd-string",
    version,
    about = "Travelling string with flowing material (Ribaric ch. 4)"
)]
struct Cli {
    #[command(subcommand)]
    study: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Natural frequencies of the analytical Galerkin model and the discrete flowing-material
    /// model at one axial speed, with the exact ones and the models' growth checked by a second
    /// discretisation.
    Modes(modes::ModesStudy),
    /// Frequencies against axial speed from 0 to past the critical speed (CSV and plot).
    Sweep(sweep::SweepStudy),
    /// Transient after a pluck below the critical speed: modal coordinates and their spectra
    /// (Ribaric Fig. 4-6 right).
    Simulate(simulate::SimulateStudy),
    /// The string partly wrapped on two pulleys, lifting off under a harmonic load.
    Wrap(wrap::WrapStudy),
}

fn main() -> ExitCode {
    let cli = flowmbd_cli::parse_args::<Cli>();
    match cli.study {
        Command::Modes(s) => run_study(crate::APP, &s, &s.common),
        Command::Sweep(s) => run_study(crate::APP, &s, &s.common),
        Command::Simulate(s) => run_study(crate::APP, &s, &s.common),
        Command::Wrap(s) => run_study(crate::APP, &s, &s.common),
    }
}
