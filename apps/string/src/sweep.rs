//! `sweep`: frequencies against axial speed from 0 to past the critical speed
//! ([`flowing::string_sweep`]).

use crate::common::*;
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CliError, CommonArgs, Study, StudyContext, StudyError};
use std::ops::ControlFlow;

use flowing::string_sweep::{SweepConfig, SweepSummary};
use flowing::string_sweep::{string_sweep, sweep_header};

/// The `sweep` study: its command line.
#[derive(clap::Args, Debug)]
pub struct SweepStudy {
    #[command(flatten)]
    pub model: ModelArgs,
    #[command(flatten)]
    pub common: CommonArgs,
}

impl Study for SweepStudy {
    type Config = SweepConfig;
    type Summary = SweepSummary;
    const NAME: &'static str = "sweep";

    fn apply_overrides(&self, c: &mut SweepConfig) {
        self.model.apply(&mut c.nodes, &mut c.modes);
    }

    fn run(&self, c: &SweepConfig, ctx: &mut StudyContext) -> Result<SweepSummary, StudyError> {
        let header = sweep_header(c.tracked);
        let mut csv = ctx.out.csv("sweep.csv", &header)?;
        let bar = ctx.progress(c.steps as f64, "speed sweep");
        // the Galerkin (columns 1..=tracked) and flowing (tracked+1..=2 tracked) frequencies
        let mut series: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 2 * c.tracked];
        let mut kept: Option<CliError> = None;
        let summary = string_sweep(c, &mut |i, row| {
            for (s, f) in series.iter_mut().zip(&row[1..=2 * c.tracked]) {
                if !f.is_nan() {
                    s.push((row[0], *f));
                }
            }
            if let Err(e) = csv.row(row) {
                kept = Some(e);
                return ControlFlow::Break(());
            }
            // interrupted: the speeds swept so far make the summary
            ctx.tick(&bar, (i + 1) as f64)
        })
        .map_err(study_error)?;
        if let Some(e) = kept {
            return Err(e.into());
        }
        csv.finish()?;
        bar.finish();
        let mut plot = LinePlot::new(
            "Travelling string: natural frequencies vs axial speed",
            "axial speed [m/s]",
            "frequency [Hz]",
        );
        for n in 0..c.tracked {
            plot = plot.with(Series::line(
                format!("Galerkin f{}", n + 1),
                series[n].clone(),
            ));
            plot = plot.with(Series::points(
                format!("flowing f{}", n + 1),
                series[c.tracked + n].clone(),
            ));
        }
        let v_max = c.max_speed_ratio * summary.critical_speed;
        let trunc_from = match (
            summary.analytical_truncation_growth_from,
            summary.flowing_truncation_growth_from,
        ) {
            (Some(a), Some(f)) => Some(a.min(f)),
            (a, f) => a.or(f),
        };
        if let Some(v0) = trunc_from {
            plot = plot.with_band(
                format!("truncation growth only, string stable (from {v0:.2} m/s)"),
                v0,
                v_max,
            );
        }
        if let Some(v0) = summary.unstable_from {
            plot = plot.with_band(format!("unstable (from {v0:.2} m/s)"), v0, v_max);
        }
        plot.save(&ctx.out.path("sweep"))?;
        Ok(summary)
    }
}
