//! `flowmbd-belt demo`: a rigid slider-crank whose crank is driven at constant angular speed,
//! integrated by generalized-α and compared with the closed-form kinematics. The configuration,
//! checks and run live in `flowmbd_cases::slider_crank_study`; this module writes
//! `history.csv` and the plot.

use flowmbd_cases::slider_crank_study::{
    DEMO_HISTORY_HEADER, DemoConfig, DemoSummary, slider_crank_demo,
};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError, set_given};

/// Command-line arguments of the demo.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// End time [s] (overrides `t_end`).
    #[arg(long)]
    t_end: Option<f64>,
}

impl Study for Args {
    type Config = DemoConfig;
    type Summary = DemoSummary;
    const NAME: &'static str = "demo";

    fn apply_overrides(&self, c: &mut DemoConfig) {
        set_given(&mut c.t_end, self.t_end);
    }

    fn run(&self, c: &DemoConfig, ctx: &mut StudyContext) -> Result<DemoSummary, StudyError> {
        let mut csv = ctx.out.csv("history.csv", &DEMO_HISTORY_HEADER)?;
        let progress = ctx.progress(c.t_end, "slider-crank");
        let (mut xs, mut refs) = (Vec::new(), Vec::new());
        let mut io_error = None;
        let summary = slider_crank_demo(c, &mut |row| {
            let [t, _, x, x_ref] = *row;
            xs.push((t, x));
            refs.push((t, x_ref));
            if let Err(e) = csv.row(row) {
                io_error.get_or_insert(e);
            }
            progress.set(t);
        })
        .map_err(StudyError::numerical)?;
        progress.finish();
        if let Some(e) = io_error {
            return Err(e.into());
        }
        csv.finish()?;
        LinePlot::new("Slider-crank: slider position", "t [s]", "x [m]")
            .with(Series::line("generalized-α", xs))
            .with(Series::line("closed form", refs))
            .save(&ctx.out.path("slider"))?;
        Ok(summary)
    }
}
