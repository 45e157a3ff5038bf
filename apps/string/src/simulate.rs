//! `simulate`: transient of the travelling string after a pluck, modal coordinates and their
//! spectra (Ribaric Fig. 4-6 right: each modal coordinate vibrates at several frequencies;
//! [`flowing::string_simulate`]).

use crate::common::*;
use flowing::string_simulate::{
    SimulateConfig, SimulateSummary, history_header, history_rows, spectra_header, spectra_rows,
    string_simulate,
};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError};

/// The `simulate` study: its command line.
#[derive(clap::Args, Debug)]
pub struct SimulateStudy {
    #[command(flatten)]
    pub speed: SpeedArg,
    #[command(flatten)]
    pub common: CommonArgs,
}

impl Study for SimulateStudy {
    type Config = SimulateConfig;
    type Summary = SimulateSummary;
    const NAME: &'static str = "simulate";

    fn apply_overrides(&self, c: &mut SimulateConfig) {
        self.speed.apply(&mut c.speed);
    }

    fn run(
        &self, c: &SimulateConfig, ctx: &mut StudyContext,
    ) -> Result<SimulateSummary, StudyError> {
        let bar = ctx.progress(c.duration, "RK4");
        let r = string_simulate(c, &mut |t| ctx.tick(&bar, t)).map_err(study_error)?;
        bar.finish();
        let (summary, hist, spectra) = (r.summary, r.history, r.spectra);
        let k = c.modes;
        // mass-normalised modes: the modal coordinates carry √kg·m
        let header = history_header(k);
        ctx.out
            .write_csv("modal_history.csv", &header, history_rows(&hist))?;
        let header = spectra_header(k);
        ctx.out
            .write_csv("spectra.csv", &header, spectra_rows(&spectra))?;
        let fmax = summary.model_hz.get(k.min(6) - 1).copied().unwrap_or(200.0) * 1.3;
        let mut plot = LinePlot::new(
            "Spectra of the modal coordinates",
            "frequency [Hz]",
            "amplitude",
        );
        for (m, s) in spectra.iter().enumerate().take(5) {
            let pts: Vec<(f64, f64)> = s
                .frequencies
                .iter()
                .zip(&s.amplitudes)
                .filter(|(f, _)| **f <= fmax)
                .map(|(f, a)| (*f, *a))
                .collect();
            plot = plot.with(Series::line(format!("z{}", m + 1), pts));
        }
        plot.save(&ctx.out.path("spectra"))?;
        let mut plot = LinePlot::new("Modal coordinates after the pluck", "t [s]", "z [√kg·m]");
        for m in 0..k.min(3) {
            let pts: Vec<(f64, f64)> = hist
                .t
                .iter()
                .zip(&hist.q)
                .filter(|(t, _)| **t <= 0.25)
                .map(|(t, q)| (*t, q[m]))
                .collect();
            plot = plot.with(Series::line(format!("z{}", m + 1), pts));
        }
        plot.save(&ctx.out.path("modal_history"))?;
        Ok(summary)
    }
}
