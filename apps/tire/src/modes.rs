//! `flowmbd-tire modes`: eigenfrequencies of the generated tire with the rim fixed, full FE model
//! (sparse shift-invert) against the reduced model (Ribaric §8.2 validation).

use crate::common::{TireSource, tire_err};
use flowing::tire::full_frequencies_hz;
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, Validate, run_study};
use serde::{Deserialize, Serialize};
use std::process::ExitCode;

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: CommonArgs,
}

/// Configuration.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The tire.
    pub tire: TireSource,
    /// Number of modes compared.
    pub count: usize,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            count: 30,
        }
    }
}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        if self.count == 0 {
            return Err(InputError::new("count", "must be positive"));
        }
        self.tire.validate()
    }
}

/// Summary.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// Full FE frequencies [Hz].
    pub full_hz: Vec<f64>,
    /// Reduced frequencies [Hz].
    pub reduced_hz: Vec<f64>,
    /// Largest relative error below 240 Hz.
    pub max_rel_error_below_240hz: f64,
}

struct Modes;

impl Study for Modes {
    type Config = Config;
    type Summary = Summary;
    const APP: &'static str = "tire";
    const NAME: &'static str = "modes";

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let fe = c.tire.fe_model()?;
        let full = full_frequencies_hz(&fe, c.count).map_err(tire_err)?;
        let red = c.tire.reduced(ctx.quiet)?;
        let mut reduced = red.frequencies_hz().map_err(tire_err)?;
        reduced.truncate(full.len());
        let err = full
            .iter()
            .zip(&reduced)
            .filter(|(f, _)| **f < 240.0)
            .map(|(f, r)| (r - f).abs() / f)
            .fold(0.0, f64::max);
        ctx.out.write_csv(
            "modes.csv",
            &["mode", "full_hz", "reduced_hz"],
            full.iter()
                .zip(&reduced)
                .enumerate()
                .map(|(i, (f, r))| vec![(i + 1) as f64, *f, *r]),
        )?;
        let pts = |f: &[f64]| -> Vec<(f64, f64)> {
            f.iter()
                .enumerate()
                .map(|(i, f)| ((i + 1) as f64, *f))
                .collect()
        };
        LinePlot::new(
            "Eigenfrequencies with the rim fixed: full FE vs reduced",
            "mode",
            "f [Hz]",
        )
        .with(Series::points("full FE", pts(&full)))
        .with(Series::points("reduced", pts(&reduced)))
        .save(&ctx.out.path("modes"))?;
        Ok(Summary {
            full_hz: full,
            reduced_hz: reduced,
            max_rel_error_below_240hz: err,
        })
    }
}

/// Run the study.
pub fn run(args: &Args) -> ExitCode {
    run_study(&Modes, &args.common)
}
