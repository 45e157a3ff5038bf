//! `flowmbd-belt`: belt-drive studies.
//!
//! Subcommands (one per study; `--help` on each lists its options):
//! - `speed-loss` (the default): angular speed loss against load torque of the flowing-material
//!   belt drive (Ribaric ch. 5–6, Table 6-1) with Bechtel's analytical line;
//! - `ancf`: the planar ANCF belt drive of Kerkkänen ch. 3;
//! - `plate`: the three-dimensional plate-belt drive of Kerkkänen ch. 4 with Bechtel's steady
//!   analytical model;
//! - `fead`: a passenger-car front-end accessory drive with an automatic tensioner over an
//!   engine-speed sweep (issue 17);
//! - `design`: the FEAD's steady design without time stepping (span tensions, tensioner arm,
//!   slip arcs, hub loads, slip margins), its modes and Campbell diagram (issue 36);
//! - `wave`: rotating vs non-rotating flowing belt with a deflected span (Ribaric Fig. 6-3);
//! - `demo`: rigid-body slider-crank driven at constant speed (mbd-core demonstration).
//!
//! Run without a subcommand, the default study runs on its embedded defaults.
// Argument doc comments are clap's --help texts, where `[m]` names a unit, not a link.
#![allow(rustdoc::broken_intra_doc_links)]

use clap::{Parser, Subcommand};
use flowmbd_cli::run_study;
use std::process::ExitCode;

mod ancf;
mod ancf_shell;
mod demo;
mod design;
mod fead;
mod plate;
mod speed_loss;
mod wave;
mod wrap_csv;

/// The app's name (`flowmbd-belt`: its default output folder `out/belt/<study>`).
const APP: &str = "belt";

/// Belt-drive studies of the flowmbd toolkit.
#[derive(Debug, Parser)]
#[command(name = "flowmbd-belt", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    study: Option<Study>,
}

#[derive(Debug, Subcommand)]
enum Study {
    /// Speed loss against load torque, flowing-material belt (Ribaric Figs. 6-6, 6-7).
    SpeedLoss(speed_loss::Args),
    /// Rigid-body slider-crank with a rotational driver (mbd-core demonstration).
    Demo(demo::Args),
    /// Planar ANCF belt drive (Kerkkänen ch. 3).
    Ancf(ancf_shell::Args),
    /// Three-dimensional plate-belt drive vs Bechtel's steady model (Kerkkänen ch. 4).
    Plate(ancf_shell::Args),
    /// Front-end accessory drive with a tensioner over an engine-speed sweep.
    Fead(fead::Args),
    /// Steady FEAD design without time stepping: tensions, arm, slip margins, modes, Campbell.
    Design(design::Args),
    /// Rotating vs non-rotating flowing belt with a deflected span (Ribaric Fig. 6-3).
    Wave(wave::Args),
}

fn main() -> ExitCode {
    let cli = flowmbd_cli::parse_args::<Cli>();
    match cli.study {
        Some(Study::Demo(args)) => run_study(APP, &args, &args.common),
        Some(Study::Ancf(args)) => ancf::run(&args),
        Some(Study::Plate(args)) => plate::run(&args),
        Some(Study::SpeedLoss(args)) => run_study(APP, &args, &args.common),
        Some(Study::Wave(args)) => run_study(APP, &args, &args.common),
        Some(Study::Fead(args)) => run_study(APP, &args, &args.common),
        Some(Study::Design(args)) => run_study(APP, &args, &args.common),
        None => {
            let args = speed_loss::Args::default();
            run_study(APP, &args, &args.common)
        }
    }
}
