//! `flowmbd-tire fmu`: the FMI 3.0 co-simulation FMU of the configured tire (issue 38 item 1):
//! `tire.fmu` ([`flowmbd_tire_fmu::write_fmu`]) and a summary of its variables, frames and
//! internal step ([`flowmbd_tire_fmu::FmuSummary`]).

use crate::common::{TireSourceExt, tire_err};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError};
use flowmbd_tire_fmu::study::LIBRARY_ENV;
use flowmbd_tire_fmu::{FmuConfig as Config, FmuError, FmuSummary as Summary};
use std::path::PathBuf;

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// The compiled FMU library to pack (`libflowmbd_tire_fmu.so`, from `cargo build --release
    /// -p flowmbd-tire-fmu`) [default: $FLOWMBD_FMU_LIB, else next to this executable].
    #[arg(long, value_name = "FILE")]
    library: Option<PathBuf>,
}

/// An FMU error: the tire's by [`tire_err`], others numerical (exit 1).
fn fmu_err(e: FmuError) -> StudyError {
    match e {
        FmuError::Tire(t) => tire_err(t),
        other => StudyError::numerical(other),
    }
}

impl Study for Args {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "fmu";

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let exe = std::env::current_exe().ok();
        let library = flowmbd_tire_fmu::find_library(
            self.library.as_deref(),
            std::env::var_os(LIBRARY_ENV)
                .filter(|v| !v.is_empty())
                .map(PathBuf::from),
            exe.as_deref().and_then(|e| e.parent()),
        )?;
        let red = c.tire.reduced(ctx.quiet)?;
        let path = ctx.out.path("tire.fmu");
        let start = flowmbd_tire_fmu::write_fmu(&library, &red, &c.rig, &path).map_err(fmu_err)?;
        flowmbd_tire_fmu::fmu_summary(&path, &library, &red, &c.rig, &start).map_err(fmu_err)
    }
}
