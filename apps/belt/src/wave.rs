//! `flowmbd-belt wave`: the rotating vs non-rotating belt demonstration of Ribaric §6.2
//! (Fig. 6-3): the flowing-material belt drive of Table 6-1 with a deflected upper span, at rest
//! and running at a constant (exaggerated) speed. Physics in `flowing::belt::wave`, the
//! measurements in `drives::wave`.
//!
//! Output folder: `wave.csv` (mid-span deflection and deflection centroid of both runs against
//! time), `span_deflection.png/svg` (mid-span deflection against time), `centroid.png/svg`,
//! and a VTK series of the belt loop per run (`vtk/<run>_NNNN.vtu` + `<run>.vtu.series`, the
//! deflection scaled by `vtk_scale` as in the "highly exaggerated" figure).

use belt::Layout;
use drives::wave::{RunSummary, summarize};
use fe_model::io::vtk::{PointField, polyline, write_vtu};
use flowing::belt::wave::{WaveConfig, WaveRun, wave_run};
use flowing::belt::{BeltMesh, BeltReduction, FlowingSettings};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{
    CommonArgs, InputError, Study, StudyContext, StudyError, Validate, VtkSeries, run_study,
};
use serde::{Deserialize, Serialize};
use std::process::ExitCode;

/// Command-line arguments of the `wave` study.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Belt speed of the running case [m/s] (overrides `wave.belt_speed`).
    #[arg(long)]
    pub speed: Option<f64>,
    // `[s]` stays unescaped: clap prints this doc comment as the --help text.
    /// Simulated time [s] (overrides `wave.t_end`).
    #[allow(rustdoc::broken_intra_doc_links)]
    #[arg(long)]
    pub t_end: Option<f64>,
}

/// Configuration (SI units).
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The drive (Ribaric Table 6-1); the bump starts on span 0 (pulley 0 → pulley 1).
    pub drive: Layout,
    /// The flowing model's loop and reduction (all free-node modes kept and 40 elements per
    /// span by default: the wave packet needs the short wavelengths).
    pub flowing: FlowingSettings,
    /// The demonstration.
    pub wave: WaveConfig,
    /// Number of VTK frames per run.
    pub vtk_frames: usize,
    /// Scale of the deflection in the VTK files \[-\].
    pub vtk_scale: f64,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            drive: drives::table_6_1::layout(),
            flowing: FlowingSettings {
                mesh: BeltMesh {
                    span_element: 0.45 / 40.0,
                    ..BeltMesh::default()
                },
                reduction: BeltReduction { free_modes: None },
                ..FlowingSettings::default()
            },
            wave: WaveConfig::default(),
            vtk_frames: 100,
            vtk_scale: 10.0,
        }
    }
}

// the layout's merge rules (`tension` / `belt_length`, `pulleys` / `tensioner`)
impl flowmbd_cli::PartialRules for Config {
    const DROPPED_BY: &'static [(&'static str, &'static str)] = belt::PARTIAL_RULES;
}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        let drive = self.drive.resolve().map_err(|e| e.within("drive"))?;
        self.flowing.validate_within("flowing")?;
        self.flowing
            .mesh
            .check_on(drive.path())
            .map_err(|e| e.within("flowing.mesh"))?;
        self.wave.validate_within("wave")?;
        // at most one frame per recorded sample (issue 35: `vtk_frames = 1e9` was taken and
        // silently gave one frame per sample)
        if !(1..=self.wave.samples).contains(&self.vtk_frames) {
            return Err(InputError::new(
                "vtk_frames",
                format!(
                    "must lie in [1, wave.samples = {}] (one frame per recorded sample at most), got {}",
                    self.wave.samples, self.vtk_frames
                ),
            ));
        }
        if !(self.vtk_scale.is_finite() && self.vtk_scale > 0.0) {
            return Err(InputError::new("vtk_scale", "must be finite and > 0"));
        }
        Ok(())
    }
}

/// Summary (`summary.json`, `--json`).
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// Transverse wave speed `c = √(T0/ρA)` \[m/s\].
    pub wave_speed: f64,
    /// At rest.
    pub rest: RunSummary,
    /// Running.
    pub running: RunSummary,
    /// Measured frequency ratio running/rest.
    pub frequency_ratio: f64,
    /// Moving-string prediction `1 − v²/c²`.
    pub frequency_ratio_string: f64,
    /// Wall time \[s\].
    pub wall_time_s: f64,
}

struct Wave {
    args: Args,
}

/// Every `n/vtk_frames`-th recorded shape of `run` as a closed `.vtu` polyline, its deflection
/// from `base` scaled by `vtk_scale`, with the true deflection \[m\] as point data.
fn write_vtk(
    ctx: &StudyContext,
    name: &str,
    run: &WaveRun,
    base: &[[f64; 2]],
    c: &Config,
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
        write_vtu(&path, &polyline(&points, true), &[deflection]).map_err(|e| {
            StudyError::Cli(flowmbd_cli::CliError::Write {
                path: path.clone(),
                message: e.to_string(),
            })
        })?;
    }
    frames.finish(&ctx.out)?;
    Ok(())
}

impl Study for Wave {
    type Config = Config;
    type Summary = Summary;
    const APP: &'static str = "belt";
    const NAME: &'static str = "wave";

    fn meaning(&self) -> &'static str {
        "The flowing-material belt drive of Ribaric Fig. 6-3 with one span deflected and let \
         go, once at rest and once running at the belt speed. wave_speed is the transverse \
         wave speed c = sqrt(T0/(rho A)) [m/s]; rest and running hold the span's measured \
         vibration in each case; frequency_ratio is the running span's lowest frequency over \
         the resting one, and frequency_ratio_string the travelling-string prediction 1 - \
         v^2/c^2 (Wickert and Mote): the axial motion lowers the span's frequencies, and the \
         two ratios agree when the span behaves like a travelling string."
    }

    fn apply_overrides(&self, c: &mut Config) {
        if let Some(v) = self.args.speed {
            c.wave.belt_speed = v;
        }
        if let Some(t) = self.args.t_end {
            c.wave.t_end = t;
        }
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let start = std::time::Instant::now();
        let progress = ctx.progress(2.0, "wave");
        let num = |e: flowing::FlowError| match e {
            flowing::FlowError::InvalidInput { item, reason } => {
                StudyError::Input(InputError::new(item, reason))
            }
            other => StudyError::numerical(other),
        };
        let drive = c
            .drive
            .resolve()
            .map_err(|e| StudyError::Input(e.within("drive")))?;
        let rest = wave_run(&drive, &c.flowing, &c.wave, false).map_err(num)?;
        progress.set(1.0);
        let running = wave_run(&drive, &c.flowing, &c.wave, true).map_err(num)?;
        progress.finish();
        let m = summarize(&drive, &c.wave, &rest, &running);
        let base = flowing::belt::BeltFe::new(&drive, &c.flowing.mesh)
            .map_err(num)?
            .position
            .clone();
        write_vtk(ctx, "rest", &rest, &base, c)?;
        write_vtk(ctx, "running", &running, &base, c)?;
        ctx.out.write_csv(
            "wave.csv",
            &[
                "t_s",
                "midspan_rest_m",
                "midspan_running_m",
                "centroid_rest_m",
                "centroid_running_m",
            ],
            (0..rest.times.len()).map(|k| {
                [
                    rest.times[k],
                    rest.midspan[k],
                    running.midspan[k],
                    rest.centroid[k],
                    running.centroid[k],
                ]
            }),
        )?;
        let ms = |r: &WaveRun| -> Vec<(f64, f64)> {
            r.times
                .iter()
                .zip(&r.midspan)
                .map(|(t, w)| (1e3 * t, 1e3 * w))
                .collect()
        };
        LinePlot::new(
            "Mid-span deflection of the upper span (Ribaric Fig. 6-3)",
            "t [ms]",
            "deflection [mm]",
        )
        .with(Series::line("at rest", ms(&rest)))
        .with(Series::line(
            format!("running at {} m/s", c.wave.belt_speed),
            ms(&running),
        ))
        .save(&ctx.out.path("span_deflection"))?;
        let t_free = m.free_time;
        let cen = |r: &WaveRun| -> Vec<(f64, f64)> {
            r.times
                .iter()
                .zip(&r.centroid)
                .filter(|(t, x)| **t <= 4.0 * t_free && x.is_finite())
                .map(|(t, x)| (1e3 * t, *x))
                .collect()
        };
        LinePlot::new(
            "Centroid of the span deflection",
            "t [ms]",
            "position along the span [m]",
        )
        .with(Series::line("at rest", cen(&rest)))
        .with(Series::line(
            format!("running at {} m/s", c.wave.belt_speed),
            cen(&running),
        ))
        .save(&ctx.out.path("centroid"))?;
        Ok(Summary {
            wave_speed: m.wave_speed,
            frequency_ratio: m.frequency_ratio,
            frequency_ratio_string: m.frequency_ratio_string,
            rest: m.rest,
            running: m.running,
            wall_time_s: start.elapsed().as_secs_f64(),
        })
    }
}

/// Run the `wave` study under the app conventions.
pub fn run(args: &Args) -> ExitCode {
    run_study(&Wave { args: args.clone() }, &args.common)
}
