//! `flowmbd-tire`: the reduced FE truck tire with flowing material (Ribaric ch. 7-8).
//!
//! Subcommands (one per study; `--help` on each lists its options):
//! - `modes`: eigenfrequencies of the generated tire (rim fixed), full FE vs reduced;
//! - `reduce`: the reduction of §8.2, saved as a reduced-tire file and timed;
//! - `cleat`: the cleat test of §8.3 at one speed (`--speed 60 --json`);
//! - `sweep`: the speed sweep 20-100 km/h (Figs. 8-7, 8-8, 8-14);
//! - `pressure`: the patch force distribution on the drum and on a flat road (Fig. 8-12);
//! - `rotating-modes`: complex modes of the rolling tire in the ground frame at several speeds
//!   (forward/backward waves, Campbell diagram);
//! - `steady`: steady-state side force, aligning moment and longitudinal force on a flat road
//!   over slip angle and drive torque (issue 38);
//! - `fmu`: the FMI 3.0 co-simulation FMU of the tire driven by its wheel-centre motion
//!   (issue 38);
//! - `dips`: the speed dips of the cleat test, predicted from the enveloping profile and the
//!   loaded vertical mode, and measured by a sweep (drum and road).
// Argument doc comments are clap's --help texts, where `[m]` names a unit, not a link.
#![allow(rustdoc::broken_intra_doc_links)]

use clap::{Parser, Subcommand};
use flowmbd_cli::{CommonArgs, run_study};
use std::process::ExitCode;

mod cleat;
mod common;
mod dips;
mod fmu;
mod maps;
mod modes;
mod pressure;
mod reduce;
mod rotating;
mod steady;
mod sweep;

/// The app's name (`flowmbd-tire`: its default output folder `out/tire/<study>`).
const APP: &str = "tire";

/// Reduced FE tire studies of the flowmbd toolkit.
#[derive(Debug, Parser)]
#[command(name = "flowmbd-tire", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    study: Option<Study>,
}

#[derive(Debug, Subcommand)]
enum Study {
    /// Eigenfrequencies of the tire with the rim fixed: full FE model and reduced model.
    Modes(CommonArgs),
    /// Reduce the generated tire (Ribaric §8.2) and save the reduced-tire file.
    Reduce(CommonArgs),
    /// Cleat test at one speed (Ribaric §8.3).
    Cleat(cleat::Args),
    /// Speed sweep of the cleat test (Ribaric Figs. 8-7, 8-8, 8-14).
    Sweep(sweep::Args),
    /// Patch force distribution on the drum and on a flat road (Ribaric Fig. 8-12).
    Pressure(CommonArgs),
    /// Complex modes of the rolling tire in the ground frame: forward/backward waves of each
    /// circumferential order vs speed (Campbell diagram), free and loaded.
    RotatingModes(rotating::Args),
    /// Speed dips of the cleat test: enveloping-filter prediction and cleat sweep, drum and
    /// road (Ribaric §8.3, §8.5).
    Dips(dips::Args),
    /// Steady-state characteristics on a flat road: Fy and Mz against slip angle, cornering
    /// stiffness, pneumatic trail, Fx against longitudinal slip (issue 38).
    Steady(steady::Args),
    /// FMI 3.0 co-simulation FMU of the tire driven by its wheel-centre motion: `tire.fmu`
    /// with the compiled library, the reduced tire and the rig (issue 38).
    Fmu(fmu::Args),
}

fn main() -> ExitCode {
    let cli = flowmbd_cli::parse_args::<Cli>();
    match cli.study {
        Some(Study::Modes(a)) => run_study(APP, &modes::Modes, &a),
        Some(Study::Reduce(a)) => run_study(APP, &reduce::Reduce, &a),
        Some(Study::Cleat(a)) => run_study(APP, &a, &a.common),
        Some(Study::Sweep(a)) => run_study(APP, &a, &a.common),
        Some(Study::Pressure(a)) => run_study(APP, &pressure::Pressure, &a),
        Some(Study::RotatingModes(a)) => run_study(APP, &a, &a.common),
        Some(Study::Dips(a)) => run_study(APP, &a, &a.common),
        Some(Study::Steady(a)) => run_study(APP, &a, &a.common),
        Some(Study::Fmu(a)) => run_study(APP, &a, &a.common),
        None => {
            let a = cleat::Args::default();
            run_study(APP, &a, &a.common)
        }
    }
}
