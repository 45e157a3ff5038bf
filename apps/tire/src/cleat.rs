//! `flowmbd-tire cleat`: the cleat test of Ribaric §8.3 at one speed (drum or flat road):
//! spindle forces `F_x`, `F_y` against time, their spectra, and the patch VTK series.

use crate::common::{RigFlags, TireSource, rig_err};
use fe_model::io::vtk::{PointField, write_vtu};
use fe_model::{Cell, CellKind, Mesh};
use flowing::tire::{
    LineMode, PEAK_BAND_HZ, ReducedTire, RigConfig, RigResult, RollingTire, RotatingOptions,
    SpindleComponent, TireError, held_nodes, line_modes, run_cleat_observed,
};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{
    CliError, CommonArgs, InputError, Study, StudyContext, StudyError, Validate, run_study,
};
use serde::{Deserialize, Serialize};
use std::process::ExitCode;

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: CommonArgs,
    /// Speed [km/h] (overrides `rig.speed_kmh`).
    #[arg(long)]
    speed: Option<f64>,
    #[command(flatten)]
    rig: RigFlags,
}

/// Configuration.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The tire.
    pub tire: TireSource,
    /// The rig.
    pub rig: RigConfig,
    /// Write a VTK (`.vtu`) snapshot of the deformed contact patch every this many steps
    /// (0 = none) into `vtk/`.
    pub vtk_every: usize,
    /// Write a VTK (`.vtu`) snapshot of the whole deforming tire (every ring at the
    /// reduction's visualisation stations, as closed polylines, with the displacement field)
    /// every this many steps (0 = none) into `vtk/` (needs a reduced tire made with
    /// `tire.reduction.viz_stations > 0`).
    pub vtk_tire_every: usize,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            rig: RigConfig::default(),
            vtk_every: 25,
            vtk_tire_every: 50,
        }
    }
}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        self.tire.validate()?;
        validate_rig(&self.rig)
    }
}

/// Validate rig settings: the library's checks ([`RigConfig`]'s `Validate` and
/// [`RigConfig::validate_spectrum`], what the study's spectra need), fields named by their
/// configuration path (`rig.…`).
pub fn validate_rig(rig: &RigConfig) -> Result<(), InputError> {
    rig.validate_within("rig")?;
    rig.validate_spectrum().map_err(|e| e.within("rig"))
}

/// Summary (the JSON keys first).
#[derive(Debug, Serialize)]
pub struct Summary {
    /// Speed \[km/h\].
    pub speed_kmh: f64,
    /// Wheel–tire DOF.
    pub dof: usize,
    /// Dominant frequency of the vertical force \[Hz\].
    pub fy_peak_hz: f64,
    /// Dominant frequency of the longitudinal force \[Hz\].
    pub fx_peak_hz: f64,
    /// RMS of the vertical force fluctuation after the hit \[N\].
    pub fy_rms: f64,
    /// RMS of the longitudinal force fluctuation after the hit \[N\].
    pub fx_rms: f64,
    /// Wall time of the time integration \[s\].
    pub wall_time_s: f64,
    /// Wall time per simulated second.
    pub wall_per_simulated_s: f64,
    /// CPU time of the integration per simulated second (independent of the machine load).
    pub cpu_per_simulated_s: Option<f64>,
    /// Preload deflection \[m\].
    pub preload_deflection_m: f64,
    /// Mean vertical spindle force of the steadily rolling tire before the cleat \[N\].
    pub fy_mean_before_n: f64,
    /// Mean longitudinal spindle force before the cleat (rolling resistance) \[N\].
    pub fx_mean_before_n: f64,
    /// Preload \[N\].
    pub load_n: f64,
    /// Rayleigh α \[1/s\], β \[s\].
    pub rayleigh: [f64; 2],
    /// Time steps and refactorisations of the iteration matrix.
    pub steps: usize,
    /// Refactorisations (spin-rate drift).
    pub refactors: usize,
    /// Work counters of the integration.
    pub stats: flowing::tire::StepStats,
    /// Frequency of the loaded tire's vertical in-plane mode \[Hz\] (largest effective vertical
    /// spindle mass, wheel fixed, preloaded patch held; `flowing::tire::loaded`): the
    /// reference for `fy_peak_hz`.
    pub loaded_vertical_mode_hz: Option<f64>,
    /// Frequency of the loaded tire's mode with the largest effective longitudinal spindle
    /// mass \[Hz\].
    pub loaded_longitudinal_mode_hz: Option<f64>,
    /// The mode that carries the `F_x` line (`fx_peak_hz`): the complex mode of the loaded
    /// tire rolling at the test speed (rolling preload's patch held, rig damping;
    /// `flowing::tire::lines`) with the largest participation in the longitudinal spindle
    /// force's response to longitudinal ground motion at the line frequency (`cleat` only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fx_line_mode: Option<LineMode>,
    /// The mode that carries the `F_y` line (`fy_peak_hz`), likewise for vertical motion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fy_line_mode: Option<LineMode>,
}

/// The loaded mode at the rolling speed that carries the `component` line at `hz`
/// (`flowing::tire::line_modes`: largest participation); `None` when that solve fails (the
/// run's results do not depend on it).
pub fn line_mode(
    red: &ReducedTire,
    r: &RigResult,
    component: SpindleComponent,
    hz: f64,
) -> Option<LineMode> {
    let opt = RotatingOptions {
        spin: r.samples.first()?.spin,
        alpha: r.rayleigh.alpha,
        beta: r.rayleigh.beta,
        max_hz: 1e3,
    };
    line_modes(red, &held_nodes(&r.preload), &opt, component, hz)
        .ok()?
        .into_iter()
        .next()
}

/// Summary of a rig result.
pub fn summarize(r: &RigResult) -> Summary {
    let band = PEAK_BAND_HZ;
    let (sx, sy) = r.spectra();
    let (rx, ry) = r.rms();
    // the steadily rolling tire: the last 50 ms before the first node touches the cleat (the
    // cleat enters the patch (L/2 + r)/v before it reaches the patch centre at t = 0)
    let before = r.mean_before_cleat(0.05).unwrap_or((0.0, 0.0));
    Summary {
        speed_kmh: r.speed_kmh,
        dof: r.dof,
        fy_peak_hz: sy.peak(band[0], band[1]).map_or(0.0, |p| p.0),
        fx_peak_hz: sx.peak(band[0], band[1]).map_or(0.0, |p| p.0),
        fy_rms: ry,
        fx_rms: rx,
        wall_time_s: r.wall_time_s,
        wall_per_simulated_s: r.wall_time_s / r.simulated_s.max(1e-12),
        cpu_per_simulated_s: r.cpu_time_s.map(|c| c / r.simulated_s.max(1e-12)),
        preload_deflection_m: r.preload.deflection,
        fy_mean_before_n: before.1,
        fx_mean_before_n: before.0,
        load_n: r.load,
        rayleigh: [r.rayleigh.alpha, r.rayleigh.beta],
        steps: r.samples.len(),
        refactors: r.refactors,
        stats: r.stats,
        loaded_vertical_mode_hz: r.loaded_vertical_mode.as_ref().map(|m| m.hz),
        loaded_longitudinal_mode_hz: r.loaded_longitudinal_mode.as_ref().map(|m| m.hz),
        fx_line_mode: None,
        fy_line_mode: None,
    }
}

/// Columns of the force history `forces.csv`.
const FORCE_COLUMNS: [&str; 7] = [
    "t_s",
    "fx_n",
    "fy_n",
    "f_lateral_n",
    "spin_rad_s",
    "active_nodes_count",
    "normal_sum_n",
];

/// Write the spectra and plots of a rig result under `prefix`, and its force history
/// `{prefix}forces.csv` too when `history` is set (the `cleat` study streams that file while it
/// runs instead, so that a failed run keeps it).
///
/// `lines` (e.g. [`line_mode`]'s) are marked on the spectrum plot as vertical lines at the
/// modes' frequencies, labelled with the mode.
pub fn write_outputs(
    ctx: &StudyContext,
    r: &RigResult,
    prefix: &str,
    history: bool,
    lines: &[(&str, &LineMode)],
) -> Result<(), StudyError> {
    if history {
        ctx.out.write_csv(
            &format!("{prefix}forces.csv"),
            &FORCE_COLUMNS,
            r.samples
                .iter()
                .map(|s| vec![s.t, s.fx, s.fy, s.fz, s.spin, s.active as f64, s.normal_sum]),
        )?;
    }
    let (sx, sy) = r.spectra();
    ctx.out.write_csv(
        &format!("{prefix}spectra.csv"),
        &["f_hz", "fx_amp_n", "fy_amp_n"],
        (0..sx.freq_hz.len()).map(|k| vec![sx.freq_hz[k], sx.amplitude[k], sy.amplitude[k]]),
    )?;
    let fx: Vec<(f64, f64)> = r.samples.iter().map(|s| (s.t, s.fx)).collect();
    let fy: Vec<(f64, f64)> = r.samples.iter().map(|s| (s.t, s.fy)).collect();
    LinePlot::new(
        format!("Spindle forces at {} km/h", r.speed_kmh),
        "t [s]",
        "F [N]",
    )
    .with(Series::line("Fx (longitudinal)", fx))
    .with(Series::line("Fy (vertical)", fy))
    .save(&ctx.out.path(&format!("{prefix}forces")))?;
    let lim = |s: &flowing::tire::Spectrum| -> Vec<(f64, f64)> {
        s.freq_hz
            .iter()
            .zip(&s.amplitude)
            .filter(|(f, _)| **f <= 300.0)
            .map(|(f, a)| (*f, *a))
            .collect()
    };
    let top = lim(&sx)
        .iter()
        .chain(lim(&sy).iter())
        .fold(0.0f64, |a, p| a.max(p.1));
    let mut plot = LinePlot::new(
        format!("Spectra at {} km/h", r.speed_kmh),
        "f [Hz]",
        "amplitude [N]",
    )
    .with(Series::line("Fx", lim(&sx)))
    .with(Series::line("Fy", lim(&sy)));
    for (name, m) in lines {
        let dir = match m.direction {
            flowing::tire::WaveDirection::Forward => "fwd",
            flowing::tire::WaveDirection::Backward => "bwd",
            flowing::tire::WaveDirection::Standing => "standing",
        };
        plot = plot.with(Series::line(
            format!(
                "{name} line {:.1} Hz: loaded mode {:.1} Hz, n={} {dir}, {:.0} %",
                m.line_hz,
                m.hz,
                m.n,
                100.0 * m.share
            ),
            vec![(m.hz, 0.0), (m.hz, top)],
        ));
    }
    plot.save(&ctx.out.path(&format!("{prefix}spectra")))?;
    Ok(())
}

/// The deformed contact nodes as VTK vertices with the normal force and friction force fields.
fn write_patch_vtu(path: &std::path::Path, sim: &RollingTire) -> Result<(), TireError> {
    let mut mesh = Mesh::new(3);
    for p in sim.contact_positions() {
        let i = mesh.add_node(p);
        mesh.cells.push(Cell {
            kind: CellKind::Vertex,
            nodes: vec![i],
        });
    }
    let fields = [
        PointField {
            name: "normal_force_N".into(),
            components: 1,
            values: sim.state.lambda.clone(),
        },
        PointField {
            name: "friction_force_N".into(),
            components: 3,
            values: sim.state.friction.iter().flatten().copied().collect(),
        },
    ];
    Ok(write_vtu(path, &mesh, &fields)?)
}

/// The whole deforming tire (visualisation rows of the reduced basis) as VTK line cells with the
/// displacement field.
fn write_tire_vtu(
    path: &std::path::Path,
    viz: &flowing::tire::VizBasis,
    sim: &RollingTire,
) -> Result<(), TireError> {
    let x = viz.deformed(&sim.state.z);
    let mut mesh = Mesh::new(3);
    for p in &x {
        mesh.add_node(*p);
    }
    for l in &viz.lines {
        mesh.cells.push(Cell {
            kind: CellKind::Line,
            nodes: vec![l[0], l[1]],
        });
    }
    let disp: Vec<f64> = x
        .iter()
        .zip(&viz.positions)
        .flat_map(|(a, s)| [a[0] - s[0], a[1] - s[1], a[2] - s[2]])
        .collect();
    let fields = [PointField {
        name: "displacement_m".into(),
        components: 3,
        values: disp,
    }];
    Ok(write_vtu(path, &mesh, &fields)?)
}

struct Cleat {
    speed: Option<f64>,
    rig: RigFlags,
}

impl Study for Cleat {
    type Config = Config;
    type Summary = Summary;
    const APP: &'static str = "tire";
    const NAME: &'static str = "cleat";

    fn meaning(&self) -> &'static str {
        "The cleat test of Ribaric 8.3: the preloaded tire rolls at speed_kmh over a \
         semicircular cleat on the drum (or road) and the spindle forces are recorded. \
         fy_peak_hz and fx_peak_hz are the frequencies of the largest spectral peaks of the \
         vertical and longitudinal force after the hit (sought in 10-500 Hz): the loaded \
         tire's vertical and longitudinal modes rolling at that speed \
         (loaded_vertical_mode_hz, fx_line_mode and fy_line_mode name the modes that carry \
         them); fy_rms and fx_rms are the force fluctuations [N]; fy_mean_before_n equals the \
         load when the rolling tire is in equilibrium and fx_mean_before_n is the rolling \
         resistance [N]; preload_deflection_m is the static deflection. wall_ and \
         cpu_per_simulated_s say how fast the model runs (1 = real time)."
    }

    fn config_notes(&self, c: &Config) -> String {
        crate::common::import_notes(&c.tire)
    }

    fn apply_overrides(&self, c: &mut Config) {
        if let Some(v) = self.speed {
            c.rig.speed_kmh = v;
        }
        self.rig.apply(&mut c.tire, &mut c.rig);
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let red = c.tire.reduced(ctx.quiet)?;
        let bar = ctx.progress(1.0, "cleat test");
        let vtk_dir = ctx.out.path("vtk");
        if c.vtk_every > 0 {
            std::fs::create_dir_all(&vtk_dir)
                .map_err(|e| StudyError::numerical(format!("{}: {e}", vtk_dir.display())))?;
        }
        if c.vtk_tire_every > 0 && red.viz.is_none() && !ctx.quiet {
            eprintln!(
                "note: the reduced tire has no visualisation rows (reduce again with \
                 tire.reduction.viz_stations > 0 for the whole-tire VTK series)"
            );
        }
        if c.vtk_tire_every > 0 && red.viz.is_some() {
            std::fs::create_dir_all(&vtk_dir)
                .map_err(|e| StudyError::numerical(format!("{}: {e}", vtk_dir.display())))?;
        }
        let every = c.vtk_every;
        let tire_every = c.vtk_tire_every;
        let viz = red.viz.as_ref();
        // the force history is streamed (same rows as `RigResult::samples`), so that a run that
        // fails keeps the history up to the failure
        let settle = c.rig.settle_time;
        let mut history = ctx.out.csv("forces.csv", &FORCE_COLUMNS)?;
        let mut history_err: Option<CliError> = None;
        let mut done = (0usize, f64::NAN);
        let mut observer = |k: usize, sim: &RollingTire| -> Result<(), TireError> {
            let f = sim.spindle_force();
            let t = sim.state.t - settle;
            let row = [
                t,
                f.fx,
                f.fy,
                f.fz,
                sim.state.theta_d,
                sim.active_count() as f64,
                sim.total_normal_force(),
            ];
            if let Err(e) = history.row(&row) {
                let reason = e.to_string();
                history_err = Some(e);
                return Err(TireError::Simulation {
                    time: sim.state.t,
                    reason,
                });
            }
            done = (k + 1, t);
            if every > 0 && k.is_multiple_of(every) {
                write_patch_vtu(&vtk_dir.join(format!("patch_{:05}.vtu", k / every)), sim)?;
            }
            if let Some(v) = viz
                && tire_every > 0
                && k.is_multiple_of(tire_every)
            {
                write_tire_vtu(
                    &vtk_dir.join(format!("tire_{:05}.vtu", k / tire_every)),
                    v,
                    sim,
                )?;
            }
            Ok(())
        };
        let result = run_cleat_observed(&red, &c.rig, &mut |f| bar.set(f), &mut observer);
        let r = match result {
            Ok(r) => {
                history.finish()?;
                r
            }
            Err(e) => {
                let _ = history.flush();
                if let Some(e) = history_err {
                    return Err(e.into());
                }
                return Err(match rig_err(e) {
                    StudyError::Numerical { message, .. } => StudyError::Numerical {
                        message,
                        partial: Some(serde_json::json!({
                            "speed_kmh": c.rig.speed_kmh,
                            "steps_done": done.0,
                            "t_last_s": done.1,
                            "history": "forces.csv",
                        })),
                    },
                    other => other,
                });
            }
        };
        bar.finish();
        let mut s = summarize(&r);
        s.fx_line_mode = line_mode(&red, &r, SpindleComponent::Longitudinal, s.fx_peak_hz);
        s.fy_line_mode = line_mode(&red, &r, SpindleComponent::Vertical, s.fy_peak_hz);
        let lines: Vec<(&str, &LineMode)> = [("Fx", &s.fx_line_mode), ("Fy", &s.fy_line_mode)]
            .into_iter()
            .filter_map(|(n, m)| m.as_ref().map(|m| (n, m)))
            .collect();
        write_outputs(ctx, &r, "", false, &lines)?;
        Ok(s)
    }
}

/// Run the study.
pub fn run(args: &Args) -> ExitCode {
    run_study(
        &Cleat {
            speed: args.speed,
            rig: args.rig.clone(),
        },
        &args.common,
    )
}
