//! `flowmbd-beam`: Kerkkänen's §2.4 ANCF beam studies (seed 001).
//!
//! * `simply-supported`: mid-point deflection of the simply supported beam (Tables 2.1, 2.2);
//! * `cantilever`: tip of the large-deflection cantilever (Tables 2.3, 2.4);
//! * `pendulum`: falling flexible pendulum, tip history and energies (Figs 2.6, 2.7);
//! * `spinning`: spinning beam with centrifugal extension (Figs 2.10, 2.11);
//! * `ground-contact`: cantilever on rigid ground by unilateral Lagrange contact, against
//!   Euler–Bernoulli (issue 6 validation of the active-set contact).
// Argument doc comments are clap's --help texts, where `[m]` names a unit, not a link.
#![allow(rustdoc::broken_intra_doc_links)]

mod studies;

use clap::{Parser, Subcommand};
use flowmbd_cli::run_study;
use std::process::ExitCode;

/// The app's name (`flowmbd-beam`: its default output folder `out/beam/<study>`).
const APP: &str = "beam";

#[derive(Parser, Debug)]
#[command(
    name = "flowmbd-beam",
    version,
    about = "ANCF beam studies of Kerkkänen (2006), §2.4"
)]
struct Cli {
    #[command(subcommand)]
    study: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Simply supported beam under a 1000 N mid-point load (Tables 2.1/2.2).
    SimplySupported(studies::SimplySupported),
    /// Large-deflection cantilever under the tip force −5·10⁸ h³ N (Tables 2.3/2.4).
    Cantilever(studies::Cantilever),
    /// Falling flexible pendulum: tip history and energy balance (Figs 2.6/2.7).
    Pendulum(studies::Pendulum),
    /// Spinning beam: spin-up and centrifugal axial extension (Figs 2.10/2.11).
    Spinning(studies::Spinning),
    /// Cantilever under a line load q = f·q* on rigid ground (unilateral Lagrange contact).
    GroundContact(studies::GroundContact),
}

fn main() -> ExitCode {
    let cli = flowmbd_cli::parse_args::<Cli>();
    match cli.study {
        Command::SimplySupported(s) => run_study(crate::APP, &s, &s.common),
        Command::Cantilever(s) => run_study(crate::APP, &s, &s.common),
        Command::Pendulum(s) => run_study(crate::APP, &s, &s.common),
        Command::Spinning(s) => run_study(crate::APP, &s, &s.common),
        Command::GroundContact(s) => run_study(crate::APP, &s, &s.common),
    }
}
