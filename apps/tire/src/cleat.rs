//! `flowmbd-tire cleat`: the cleat test of Ribaric §8.3 at one speed (drum or flat road):
//! spindle forces `F_x`, `F_y` against time, their spectra, and the patch VTK series.

use crate::common::{RigFlags, TireSourceExt, rig_err};
use fe_model::io::vtk::{PointField, write_vtu};
use fe_model::{Cell, CellKind, Mesh};
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CliError, CommonArgs, Study, StudyContext, StudyError, VtkSeries, set_given};
use tire::{
    LineMode, RigResult, RollingTire, TireError, cleat_summary, phase_spread, run_cleat_observed,
};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    /// Speed [km/h] (overrides `rig.speed_kmh`).
    #[arg(long)]
    speed: Option<f64>,
    /// Cleat phases: repeat the test with the cleat arriving j/N of an impact step later and
    /// report the mean and spread of the line amplitudes (overrides `cleat_phases`)
    #[arg(long)]
    phases: Option<usize>,
    #[command(flatten)]
    rig: RigFlags,
}

/// Configuration and summary of the study: in the library, shared with the Python package.
pub use tire::study::{CleatStudyConfig as Config, CleatSummary as Summary};
use tire::study::{FORCE_COLUMNS, SPECTRUM_COLUMNS, force_row, sample_row, spectrum_rows};

/// Write the spectra and plots of a rig result under `prefix`, and its force history
/// `{prefix}forces.csv` too when `history` is set (the `cleat` study streams that file while it
/// runs instead, so that a failed run keeps it).
///
/// `lines` (e.g. [`tire::study::line_mode`]'s) are marked on the spectrum plot as vertical lines at the
/// modes' frequencies, labelled with the mode.
pub fn write_outputs(
    ctx: &StudyContext, r: &RigResult, prefix: &str, history: bool, lines: &[(&str, &LineMode)],
) -> Result<(), StudyError> {
    if history {
        ctx.out.write_csv(
            &format!("{prefix}forces.csv"),
            &FORCE_COLUMNS,
            r.samples.iter().map(|s| sample_row(s).to_vec()),
        )?;
    }
    let (sx, sy) = r.spectra();
    ctx.out.write_csv(
        &format!("{prefix}spectra.csv"),
        &SPECTRUM_COLUMNS,
        spectrum_rows(&sx, &sy),
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
    let lim = |s: &tire::Spectrum| -> Vec<(f64, f64)> {
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
            tire::WaveDirection::Forward => "fwd",
            tire::WaveDirection::Backward => "bwd",
            tire::WaveDirection::Standing => "standing",
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

/// The frame of `series` due at simulated time `now` \[s\] ([`VtkSeries::due`]); a write error
/// is kept in `kept` (the study reports it as such) and stops the run.
fn due_frame(
    series: &mut VtkSeries, out: &flowmbd_cli::OutputDir, now: f64, kept: &mut Option<CliError>,
) -> Result<Option<std::path::PathBuf>, TireError> {
    series.due(out, now).map_err(|e| {
        let reason = e.to_string();
        *kept = Some(e);
        TireError::Simulation { time: now, reason }
    })
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
    path: &std::path::Path, viz: &tire::VizBasis, sim: &RollingTire,
) -> Result<(), TireError> {
    let x = viz.deformed(&sim.coordinates());
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

impl Study for Args {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "cleat";

    fn apply_overrides(&self, c: &mut Config) {
        set_given(&mut c.rig.speed_kmh, self.speed);
        set_given(&mut c.cleat_phases, self.phases);
        self.rig.apply(&mut c.tire, &mut c.rig);
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let red = c.tire.reduced(ctx.quiet)?;
        let bar = ctx.progress(1.0, "cleat test");
        if c.vtk_tire_interval > 0.0 && red.viz.is_none() && !ctx.quiet {
            eprintln!(
                "note: the reduced tire has no visualisation rows (reduce again with \
                 tire.reduction.viz_stations > 0 for the whole-tire VTK series)"
            );
        }
        let mut patch_frames = VtkSeries::new("patch", "vtu", c.vtk_interval);
        let tire_interval = if red.viz.is_some() {
            c.vtk_tire_interval
        } else {
            0.0
        };
        let mut tire_frames = VtkSeries::new("tire", "vtu", tire_interval);
        let viz = red.viz.as_ref();
        // the force history is streamed (same rows as `RigResult::samples`), so that a run that
        // fails keeps the history up to the failure
        let settle = c.rig.settle_time;
        let mut history = ctx.out.csv("forces.csv", &FORCE_COLUMNS)?;
        let mut history_err: Option<CliError> = None;
        let mut done = (0usize, f64::NAN);
        let mut observer = |k: usize, sim: &RollingTire| -> Result<(), TireError> {
            let row = force_row(sim, settle);
            let t = row[0];
            if let Err(e) = history.row(&row) {
                let reason = e.to_string();
                history_err = Some(e);
                return Err(TireError::Simulation {
                    time: sim.state.t,
                    reason,
                });
            }
            done = (k + 1, t);
            let now = sim.state.t;
            if let Some(path) = due_frame(&mut patch_frames, &ctx.out, now, &mut history_err)? {
                write_patch_vtu(&path, sim)?;
            }
            if let Some(v) = viz
                && let Some(path) = due_frame(&mut tire_frames, &ctx.out, now, &mut history_err)?
            {
                write_tire_vtu(&path, v, sim)?;
            }
            Ok(())
        };
        let result = run_cleat_observed(&red, &c.rig, &mut |f| bar.set(f), &mut observer);
        // the frames written so far are indexed whether the run completed or not
        patch_frames.finish(&ctx.out)?;
        tire_frames.finish(&ctx.out)?;
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
        let mut s = cleat_summary(&red, &r);
        let lines: Vec<(&str, &LineMode)> = [("Fx", &s.fx_line_mode), ("Fy", &s.fy_line_mode)]
            .into_iter()
            .filter_map(|(n, m)| m.as_ref().map(|m| (n, m)))
            .collect();
        // phase 0's outputs are written first, so that a failure in the other phases keeps them
        write_outputs(ctx, &r, "", false, &lines)?;
        if c.cleat_phases > 1 {
            let bar = ctx.progress(1.0, "cleat phases");
            let spread =
                phase_spread(&red, &c.rig, c.cleat_phases, &s, &|f| bar.set(f)).map_err(rig_err)?;
            bar.finish();
            ctx.out.write_csv(
                "phases.csv",
                &[
                    "phase_index",
                    "cleat_delay_s",
                    "fy_band_rms_N",
                    "fx_band_rms_N",
                ],
                (0..spread.phases).map(|j| {
                    vec![
                        j as f64,
                        j as f64 / spread.phases as f64 * c.rig.impact_step(),
                        spread.fy_band_rms_n[j],
                        spread.fx_band_rms_n[j],
                    ]
                }),
            )?;
            s.phases = Some(spread);
        }
        Ok(s)
    }
}
