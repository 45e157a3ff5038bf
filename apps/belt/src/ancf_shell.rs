//! What the two ANCF studies of `flowmbd-belt` share (issue 33 item 2): the planar drive
//! (`ancf`, [`crate::ancf`]) and the plate drive (`plate`, [`crate::plate`]) are one
//! [`Study`] ([`DriveStudy`] over the study's [`AncfApp`]: arguments, `--t-end`, the error
//! mapping, the failed run's partial summary) and write their sampled outputs while they run
//! the same way ([`sampled_run`]: `history.csv`, the VTK series of the belt, the progress
//! bar).

use drives::ancf_run::{DriveStudyConfig, Due, RunEnd};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{
    CommonArgs, InputError, Study, StudyContext, StudyError, Validate, VtkSeries, run_study,
};
use mbd_core::config::PartialRules;
use mbd_core::integrators::State;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::marker::PhantomData;
use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

/// Command-line arguments of the `ancf` and `plate` studies.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// End time [s] (overrides `t_end`).
    #[arg(long)]
    pub t_end: Option<f64>,
}

/// One ANCF study of the app: its configuration (defined in `drives`, shared with the Python
/// package, which also names the summary, its meaning and the end time), its name and its run.
pub(crate) trait AncfApp {
    /// The configuration.
    type Config: DriveStudyConfig;
    /// Study name (`ancf`, `plate`).
    const NAME: &'static str;

    /// Run the study (`start`: the study's start, for its wall time).
    fn run(
        c: &Self::Config, ctx: &mut StudyContext, start: Instant,
    ) -> Result<Summary<Self>, StudyError>;
}

/// The summary of the study `A`.
pub(crate) type Summary<A> = <<A as AncfApp>::Config as DriveStudyConfig>::Summary;

/// The [`Study`] of an [`AncfApp`] (module documentation).
pub(crate) struct DriveStudy<A> {
    t_end: Option<f64>,
    app: PhantomData<A>,
}

impl<A: AncfApp> Study for DriveStudy<A>
where
    A::Config: Serialize + DeserializeOwned + Default + Validate + PartialRules,
    A::Config: schemars::JsonSchema,
{
    type Config = A::Config;
    type Summary = Summary<A>;
    const NAME: &'static str = A::NAME;
    const MEANING: &'static str = A::Config::MEANING;

    fn apply_overrides(&self, c: &mut A::Config) {
        if let Some(t) = self.t_end {
            *c.t_end_mut() = t;
        }
    }

    fn run(&self, c: &A::Config, ctx: &mut StudyContext) -> Result<Summary<A>, StudyError> {
        A::run(c, ctx, Instant::now())
    }
}

/// Run the study `A` under the app conventions.
pub(crate) fn run<A: AncfApp>(args: &Args) -> ExitCode
where
    DriveStudy<A>: Study,
{
    let study = DriveStudy::<A> {
        t_end: args.t_end,
        app: PhantomData,
    };
    run_study(crate::APP, &study, &args.common)
}

/// An ANCF error as the app reports it: bad input names the drive's field (exit 2), anything
/// else is numerical (exit 1).
pub(crate) fn to_study_error(e: ancf::AncfError) -> StudyError {
    match e {
        ancf::AncfError::InvalidInput { item, reason } => {
            StudyError::Input(InputError::new(format!("drive: {item}"), reason))
        }
        other => StudyError::numerical(other),
    }
}

/// The summary of a run (its wall time since `start`), or the numerical failure that stopped
/// it with the summary at the state reached as its partial result.
pub(crate) fn finish<S: Serialize>(
    mut summary: S, run: impl FnOnce(&mut S) -> &mut RunEnd, failure: Option<String>,
    start: Instant,
) -> Result<S, StudyError> {
    run(&mut summary).wall_time_s = start.elapsed().as_secs_f64();
    match failure {
        Some(msg) => Err(StudyError::failed_with(
            format!("integration failed: {msg}"),
            &summary,
        )),
        None => Ok(summary),
    }
}

/// The sampled outputs of a run ([`sampled_run`]): the progress bar's label, the end time
/// \[s\], the interval of the VTK frames \[s\], the pulleys' names and the columns of
/// `history.csv` after each pulley's speed.
pub(crate) struct Sampled<'a> {
    /// Progress bar label.
    pub label: &'a str,
    /// End time \[s\].
    pub t_end: f64,
    /// Interval between VTK frames \[s\].
    pub vtk_interval: f64,
    /// The pulleys' names (travel order).
    pub pulleys: Vec<String>,
    /// The columns after `t_s` and the pulleys' speeds.
    pub columns: Vec<String>,
}

/// The observer of a study's run ([`sampled_run`]): sees each sampled state and what it is
/// due for.
pub(crate) type Observer<'a> = &'a mut dyn FnMut(&State, Due) -> Result<(), StudyError>;

/// Each pulley's `(t [s], ω [rad/s])` at the history samples of a run ([`sampled_run`]).
pub(crate) type PulleySpeeds = Vec<Vec<(f64, f64)>>;

/// Run a study with its sampled outputs: `history.csv` (`t_s`, each pulley's speed
/// `omega_NAME_rad_per_s`, then `sampled.columns`; a row `[t, row(s)]` per history sample, whose
/// first values are the pulleys' speeds), a VTK series of the belt (`vtk/belt_NNNN.vtu`, a frame
/// written by `frame(s, path)` every `sampled.vtk_interval`) and a progress bar. The initial
/// state, the coordinates `q0` at rest at `t = 0`, is the first row and frame; `run` runs the
/// study with the observer that writes the others. Returns what `run` returns and each pulley's speed at the history samples, for
/// their plot.
pub(crate) fn sampled_run<T>(
    ctx: &mut StudyContext, sampled: Sampled<'_>, q0: &[f64],
    mut row: impl FnMut(&State) -> Vec<f64>,
    mut frame: impl FnMut(&State, &Path) -> Result<(), StudyError>,
    run: impl FnOnce(Observer<'_>) -> Result<T, StudyError>,
) -> Result<(T, PulleySpeeds), StudyError> {
    let mut header = vec!["t_s".to_string()];
    header.extend(
        sampled
            .pulleys
            .iter()
            .map(|n| format!("omega_{n}_rad_per_s")),
    );
    header.extend(sampled.columns);
    let hdr: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut csv = ctx.out.csv("history.csv", &hdr)?;
    let mut frames = VtkSeries::new("belt", "vtu", sampled.vtk_interval);
    let mut speeds: PulleySpeeds = vec![Vec::new(); sampled.pulleys.len()];
    let mut record = |s: &State, csv: &mut flowmbd_cli::output::CsvSink| {
        let values = row(s);
        for (sp, &w) in speeds.iter_mut().zip(&values) {
            sp.push((s.t, w));
        }
        let mut r = vec![s.t];
        r.extend(values);
        csv.row(&r)
    };
    let s0 = State::new(0.0, q0.to_vec(), vec![0.0; q0.len()]);
    record(&s0, &mut csv)?;
    frame(&s0, &frames.frame(&ctx.out, 0.0)?)?;
    let progress = ctx.progress(sampled.t_end, sampled.label);
    let out = &ctx.out;
    let end = run(&mut |s, due| {
        if due.history {
            record(s, &mut csv)?;
        }
        if due.frame {
            frame(s, &frames.frame(out, s.t)?)?;
        }
        progress.set(s.t);
        Ok(())
    })?;
    progress.finish();
    csv.finish()?;
    frames.finish(&ctx.out)?;
    Ok((end, speeds))
}

/// A plot over the time `t [s]` with one line per `(name, points)` of `lines`.
pub(crate) fn time_plot(
    title: &str, y_label: &str, lines: impl IntoIterator<Item = (String, Vec<(f64, f64)>)>,
) -> LinePlot {
    lines.into_iter().fold(
        LinePlot::new(title, "t [s]", y_label),
        |pl, (name, points)| pl.with(Series::line(name, points)),
    )
}
