//! `flowmbd-tire pressure`: the preloaded patch on the drum (R = 1.25 m) and on a flat road
//! (Ribaric Fig. 8-12, 4448 N; [`tire::pressure_study`]): contact-node forces and patch extent.

use crate::common::{TireSourceExt, tire_err};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{Study, StudyContext, StudyError};
use tire::pressure_study::{
    PATCH_COLUMNS, PressureStudyConfig as Config, PressureSummary as Summary, run_pressure,
};

/// The study.
pub struct Pressure;

impl Study for Pressure {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "pressure";

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let red = c.tire.reduced(ctx.quiet)?;
        let (summary, patches) = run_pressure(&red, c).map_err(tire_err)?;
        let mut plot = LinePlot::new(
            format!(
                "Contact-node forces at {:.0} N (drum R = {} m vs flat road)",
                c.load, c.drum_radius
            ),
            "x [m] (longitudinal position in the patch)",
            "node force [N]",
        );
        for p in &patches {
            let name = p.ground.name();
            ctx.out
                .write_csv(&format!("patch_{name}.csv"), &PATCH_COLUMNS, &p.rows)?;
            plot = plot.with(Series::points(
                name,
                p.rows
                    .iter()
                    .filter(|r| r[3] > 0.0)
                    .map(|r| (r[0], r[3]))
                    .collect(),
            ));
        }
        plot.save(&ctx.out.path("patch_forces"))?;
        Ok(summary)
    }
}
