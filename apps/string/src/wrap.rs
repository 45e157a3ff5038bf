//! `wrap`: the string partly wrapped on two pulleys (Ribaric Fig. 4-4, 4-7, (4.10), (4.11),
//! (4.31)–(4.40)), lifting off under a harmonic load; active-set Lagrange contact with event
//! location. The configuration, checks and run live in [`flowing::string_wrap`]; this module
//! writes `history.csv`, `events.csv`, the VTK frames and the plots.

use crate::common::*;
use flowing::string_wrap::{
    EVENTS_HEADER, WrapConfig, WrapSummary, event_rows, string_wrap, wrap_frame,
    wrap_history_header,
};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError};

/// The `wrap` study: its command line.
#[derive(clap::Args, Debug)]
pub struct WrapStudy {
    #[command(flatten)]
    pub speed: SpeedArg,
    #[command(flatten)]
    pub common: CommonArgs,
}

impl Study for WrapStudy {
    type Config = WrapConfig;
    type Summary = WrapSummary;
    const NAME: &'static str = "wrap";

    fn apply_overrides(&self, c: &mut WrapConfig) {
        self.speed.apply(&mut c.speed);
    }

    fn run(&self, c: &WrapConfig, ctx: &mut StudyContext) -> Result<WrapSummary, StudyError> {
        let np = c.pulleys.len();
        let mut csv = ctx.out.csv("history.csv", &wrap_history_header(np))?;
        let bar = ctx.progress(c.duration, "contact simulation");
        let mut io_err: Option<StudyError> = None;
        let mut samples = 0usize;
        let run = string_wrap(c, &mut |s| {
            if let Some(i) = s.frame {
                let path = ctx.out.path(&format!("wrap_{i:03}.vtu"));
                let written = wrap_frame(s, &c.pulleys, c.string.length)
                    .map_err(study_error)
                    .and_then(|(mesh, fields)| {
                        fe_model::io::vtk::write_vtu(&path, &mesh, &fields)
                            .map_err(|e| StudyError::numerical(format!("VTK output: {e}")))
                    });
                if let Err(e) = written {
                    io_err.get_or_insert(e);
                }
            }
            if let Some(row) = s.row {
                samples += 1;
                if let Err(e) = csv.row(row) {
                    io_err.get_or_insert(e.into());
                }
                bar.set(s.state.t);
            }
            ctx.cancel.check()
        });
        bar.finish();
        csv.finish()?;
        if let Some(e) = io_err {
            return Err(e);
        }
        let run = run.map_err(|e| match study_error(e) {
            StudyError::Numerical { message, .. } => StudyError::Numerical {
                message: format!("contact simulation failed: {message}"),
                partial: Some(serde_json::json!({ "samples": samples })),
            },
            input => input,
        })?;
        ctx.out
            .write_csv("events.csv", &EVENTS_HEADER, event_rows(&run.events))?;
        let rows = &run.history;
        let mut plot = LinePlot::new(
            "Wrapped string: active contact nodes",
            "t [s]",
            "active nodes",
        );
        for p in 0..np {
            plot = plot.with(Series::line(
                format!("pulley {p}"),
                rows.iter().map(|r| (r[0], r[4 + p])).collect(),
            ));
        }
        plot.save(&ctx.out.path("active_nodes"))?;
        let plot = LinePlot::new("Wrapped string: deflection at the load", "t [s]", "u [m]").with(
            Series::line("u(load)", rows.iter().map(|r| (r[0], r[1])).collect()),
        );
        plot.save(&ctx.out.path("deflection"))?;
        Ok(run.summary)
    }
}
