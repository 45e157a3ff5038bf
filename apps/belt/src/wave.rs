//! `flowmbd-belt wave`: the rotating vs non-rotating belt demonstration of Ribaric §6.2
//! (Fig. 6-3): the flowing-material belt drive of Table 6-1 with a deflected upper span, at rest
//! and running at a constant (exaggerated) speed. Physics in `flowing::belt::wave`, the
//! measurements in `drives::wave`.
//!
//! Output folder: `wave.csv` (mid-span deflection and deflection centroid of both runs against
//! time), `span_deflection.png/svg` (mid-span deflection against time), `centroid.png/svg`,
//! and a VTK series of the belt loop per run (`vtk/<run>_NNNN.vtu` + `<run>.vtu.series`, the
//! deflection scaled by `vtk_scale` as in the "highly exaggerated" figure).

use drives::wave::{
    WAVE_CSV_HEADER, WaveStudyConfig, WaveStudySummary, run_wave_study, wave_csv_rows,
};
use fe_model::io::vtk::{PointField, polyline, write_vtu};
use flowing::belt::wave::WaveRun;
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, VtkSeries, set_given};

/// Command-line arguments of the `wave` study.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Belt speed of the running case [m/s] (overrides `wave.belt_speed`).
    #[arg(long)]
    pub speed: Option<f64>,
    /// Simulated time [s] (overrides `wave.t_end`).
    #[arg(long)]
    pub t_end: Option<f64>,
}

/// Every `n/vtk_frames`-th recorded shape of `run` as a closed `.vtu` polyline, its deflection
/// from `base` scaled by `vtk_scale`, with the true deflection \[m\] as point data.
fn write_vtk(
    ctx: &StudyContext, name: &str, run: &WaveRun, base: &[[f64; 2]], c: &WaveStudyConfig,
) -> Result<(), StudyError> {
    let mut frames = VtkSeries::new(name, "vtu", 0.0);
    let every = run.times.len().div_ceil(c.vtk_frames).max(1);
    for (t, shape) in run.times.iter().zip(&run.shapes).step_by(every) {
        let points: Vec<[f64; 3]> = shape
            .iter()
            .zip(base)
            .map(|(p, b)| {
                [
                    b[0] + c.vtk_scale * (p[0] - b[0]),
                    b[1] + c.vtk_scale * (p[1] - b[1]),
                    0.0,
                ]
            })
            .collect();
        let deflection = PointField {
            name: "deflection_m".into(),
            components: 1,
            values: shape
                .iter()
                .zip(base)
                .map(|(p, b)| (p[0] - b[0]).hypot(p[1] - b[1]))
                .collect(),
        };
        let path = frames.frame(&ctx.out, *t)?;
        write_vtu(&path, &polyline(&points, true), &[deflection])
            .map_err(|e| flowmbd_cli::CliError::write(&path, e))?;
    }
    frames.finish(&ctx.out)?;
    Ok(())
}

impl Study for Args {
    type Config = WaveStudyConfig;
    type Summary = WaveStudySummary;
    const NAME: &'static str = "wave";

    fn apply_overrides(&self, c: &mut WaveStudyConfig) {
        set_given(&mut c.wave.belt_speed, self.speed);
        set_given(&mut c.wave.t_end, self.t_end);
    }

    fn run(
        &self, c: &WaveStudyConfig, ctx: &mut StudyContext,
    ) -> Result<WaveStudySummary, StudyError> {
        let progress = ctx.progress(1.0, "wave");
        let study = run_wave_study(c, |f| progress.set(f)).map_err(|e| match e {
            flowing::FlowError::InvalidInput { item, reason } => {
                StudyError::Input(InputError::new(item, reason))
            }
            other => StudyError::numerical(other),
        })?;
        progress.finish();
        let (rest, running) = (&study.rest, &study.running);
        write_vtk(ctx, "rest", rest, &study.reference, c)?;
        write_vtk(ctx, "running", running, &study.reference, c)?;
        ctx.out
            .write_csv("wave.csv", &WAVE_CSV_HEADER, wave_csv_rows(rest, running))?;
        let ms = |r: &WaveRun| -> Vec<(f64, f64)> {
            r.times
                .iter()
                .zip(&r.midspan)
                .map(|(t, w)| (1e3 * t, 1e3 * w))
                .collect()
        };
        let both = |title: &str, y: &str, of: &dyn Fn(&WaveRun) -> Vec<(f64, f64)>, stem| {
            LinePlot::new(title, "t [ms]", y)
                .with(Series::line("at rest", of(rest)))
                .with(Series::line(
                    format!("running at {} m/s", c.wave.belt_speed),
                    of(running),
                ))
                .save(&ctx.out.path(stem))
        };
        both(
            "Mid-span deflection of the upper span (Ribaric Fig. 6-3)",
            "deflection [mm]",
            &ms,
            "span_deflection",
        )?;
        let t_free = study.free_time;
        let cen = |r: &WaveRun| -> Vec<(f64, f64)> {
            r.times
                .iter()
                .zip(&r.centroid)
                .filter(|(t, x)| **t <= 4.0 * t_free && x.is_finite())
                .map(|(t, x)| (1e3 * t, *x))
                .collect()
        };
        both(
            "Centroid of the span deflection",
            "position along the span [m]",
            &cen,
            "centroid",
        )?;
        Ok(study.summary)
    }
}
