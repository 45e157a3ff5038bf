//! `flowmbd-beam`: Kerkkänen's §2.4 ANCF beam studies (seed 001).
//!
//! * `simply-supported`: mid-point deflection of the simply supported beam (Tables 2.1, 2.2);
//! * `cantilever`: tip of the large-deflection cantilever (Tables 2.3, 2.4);
//! * `pendulum`: falling flexible pendulum, tip history and energies (Figs 2.6, 2.7);
//! * `spinning`: spinning beam with centrifugal extension (Figs 2.10, 2.11);
//! * `ground-contact`: cantilever on rigid ground by unilateral Lagrange contact, against
//!   Euler–Bernoulli (issue 6 validation of the active-set contact).

mod studies;

use ancf::beam_mesh::BeamElementKind;
use clap::{Parser, Subcommand, ValueEnum};
use flowmbd_cli::{CommonArgs, run_study};
use std::process::ExitCode;

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

/// Element choice on the command line.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum ElementArg {
    /// Kerkkänen's proposed 8-DOF linear shear-deformable element.
    Proposed,
    /// The Omar–Shabana 12-DOF element.
    OmarShabana,
}

impl From<ElementArg> for BeamElementKind {
    fn from(e: ElementArg) -> Self {
        match e {
            ElementArg::Proposed => BeamElementKind::Proposed,
            ElementArg::OmarShabana => BeamElementKind::OmarShabana,
        }
    }
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Simply supported beam under a 1000 N mid-point load (Tables 2.1/2.2).
    SimplySupported {
        /// Element type.
        #[arg(long, value_enum)]
        element: Option<ElementArg>,
        /// Poisson's ratio.
        #[arg(long)]
        nu: Option<f64>,
        /// Number of elements (even).
        #[arg(long)]
        elements: Option<usize>,
        #[command(flatten)]
        common: CommonArgs,
    },
    /// Large-deflection cantilever under the tip force −5·10⁸ h³ N (Tables 2.3/2.4).
    Cantilever {
        /// Element type.
        #[arg(long, value_enum)]
        element: Option<ElementArg>,
        // `[m]` stays unescaped: clap prints this doc comment as the --help text.
        /// Section height h [m].
        #[allow(rustdoc::broken_intra_doc_links)]
        #[arg(long)]
        h: Option<f64>,
        /// Poisson's ratio.
        #[arg(long)]
        nu: Option<f64>,
        /// Number of elements.
        #[arg(long)]
        elements: Option<usize>,
        #[command(flatten)]
        common: CommonArgs,
    },
    /// Falling flexible pendulum: tip history and energy balance (Figs 2.6/2.7).
    Pendulum {
        /// Number of elements.
        #[arg(long)]
        elements: Option<usize>,
        #[command(flatten)]
        common: CommonArgs,
    },
    /// Spinning beam: spin-up and centrifugal axial extension (Figs 2.10/2.11).
    Spinning {
        /// Number of elements.
        #[arg(long)]
        elements: Option<usize>,
        #[command(flatten)]
        common: CommonArgs,
    },
    /// Cantilever under a line load q = f·q* on rigid ground (unilateral Lagrange contact).
    GroundContact {
        /// Element type.
        #[arg(long, value_enum)]
        element: Option<ElementArg>,
        /// Number of elements.
        #[arg(long)]
        elements: Option<usize>,
        /// Line load as a multiple f of the critical load q* = 72 EI g₀/L⁴.
        #[arg(long)]
        load_factor: Option<f64>,
        #[command(flatten)]
        common: CommonArgs,
    },
}

fn main() -> ExitCode {
    let cli = flowmbd_cli::parse_args::<Cli>();
    match cli.study {
        Command::SimplySupported {
            element,
            nu,
            elements,
            common,
        } => run_study(
            &studies::SimplySupported {
                element: element.map(Into::into),
                nu,
                elements,
            },
            &common,
        ),
        Command::Cantilever {
            element,
            h,
            nu,
            elements,
            common,
        } => run_study(
            &studies::Cantilever {
                element: element.map(Into::into),
                h,
                nu,
                elements,
            },
            &common,
        ),
        Command::Pendulum { elements, common } => {
            run_study(&studies::Pendulum { elements }, &common)
        }
        Command::Spinning { elements, common } => {
            run_study(&studies::Spinning { elements }, &common)
        }
        Command::GroundContact {
            element,
            elements,
            load_factor,
            common,
        } => run_study(
            &studies::GroundContact {
                element: element.map(Into::into),
                elements,
                load_factor,
            },
            &common,
        ),
    }
}
