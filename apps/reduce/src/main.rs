//! `flowmbd-reduce`: model-reduction studies of the flowmbd toolkit.
//!
//! Subcommands (one module each; `--help` on each lists its options):
//! - `modes`: lowest modes of `K φ = λ M φ` read from Matrix Market files;
//! - `tire-mesh`: the generated truck-tire carcass, its M and K as Matrix Market, mesh as VTK
//!   and node sets as JSON;
//! - `lin-beam`: Lin ch. 6, 7.1 and 8.5 on the Appendix A beam;
//! - `lin-slab`: Lin §7.2 simulations on the Appendix B slab (NR, GR, MT, CB, MC);
//! - `reduce`: reduce user Matrix Market matrices and write the reduced model.
// Argument doc comments are clap's --help texts, where `[m]` names a unit, not a link.
#![allow(rustdoc::broken_intra_doc_links)]

use clap::{Parser, Subcommand};
use flowmbd_cli::{CommonArgs, run_study};
use std::process::ExitCode;

mod lin_beam;
mod lin_slab;
mod modes;
mod reduce_cmd;
mod tire_mesh;

/// The app's name (`flowmbd-reduce`: its default output folder `out/reduce/<study>`).
const APP: &str = "reduce";

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
    TireMesh(CommonArgs),
    /// Lin ch. 6-8 on the Appendix A beam: frequencies, Guyan models, profile tests, mean axes.
    LinBeam(CommonArgs),
    /// Lin §7.2 simulations 1-3 on the Appendix B slab: NR, Guyan, modal truncation, CB, MC.
    LinSlab(CommonArgs),
    /// Reduce Matrix Market M and K with a boundary node set; write the reduced model.
    Reduce(reduce_cmd::Args),
}

fn main() -> ExitCode {
    match flowmbd_cli::parse_args::<Cli>().study {
        Study::Modes(args) => run_study(APP, &args, &args.common),
        Study::TireMesh(args) => run_study(APP, &tire_mesh::TireMesh, &args),
        Study::LinBeam(args) => run_study(APP, &lin_beam::LinBeamStudy, &args),
        Study::LinSlab(args) => run_study(APP, &lin_slab::LinSlabStudy, &args),
        Study::Reduce(args) => reduce_cmd::run(args),
    }
}
