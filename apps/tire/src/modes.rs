//! `flowmbd-tire modes`: eigenfrequencies of the generated tire with the rim fixed, full FE model
//! (sparse shift-invert) against the reduced model (Ribaric §8.2 validation), and the modes of
//! the loaded tire (reduced, preloaded patch held on the ground, wheel fixed) with their
//! effective spindle masses ([`tire::modes_study`]): the vertical in-plane mode the cleat test
//! should show (Ribaric §8.3).

use crate::common::{TireSourceExt, tire_err};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{Study, StudyContext, StudyError};
use tire::modes_study::{
    LOADED_COLUMNS, MODES_COLUMNS, ModesStudyConfig as Config, ModesSummary as Summary,
    loaded_rows, modes_rows, run_modes,
};

/// The study.
pub struct Modes;

impl Study for Modes {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "modes";

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let fe = c.tire.fe_model_or_err()?;
        let red = c.tire.reduced(ctx.quiet)?;
        let (summary, loaded) = run_modes(&fe, &red, c).map_err(tire_err)?;
        ctx.out
            .write_csv("modes.csv", &MODES_COLUMNS, modes_rows(&summary))?;
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
        .with(Series::points("full FE", pts(&summary.full_hz)))
        .with(Series::points("reduced", pts(&summary.reduced_hz)))
        .save(&ctx.out.path("modes"))?;
        ctx.out
            .write_csv("loaded_modes.csv", &LOADED_COLUMNS, loaded_rows(&loaded))?;
        Ok(summary)
    }
}
