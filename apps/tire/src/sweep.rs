//! `flowmbd-tire sweep`: the cleat test at 20, 30, ..., 100 km/h (Ribaric Figs. 8-7, 8-8 on the
//! drum, 8-14 on the flat road; [`tire::sweep_study`]): peak spectral amplitudes against speed
//! and the spectra as a speed × frequency table for contour/waterfall plots.

use crate::common::{RigFlags, rig_err, run_reduced};
use crate::maps::SpectrumMap;
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, Study, StudyContext, StudyError};
use tire::TireError;
use tire::sweep_study::{
    SweepStudyConfig as Config, SweepSummary as Summary, WATERFALL_COLUMNS, matrix_header,
    run_sweep,
};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    pub common: CommonArgs,
    #[command(flatten)]
    rig: RigFlags,
}

impl Study for Args {
    type Config = Config;
    type Summary = Summary;
    const NAME: &'static str = "sweep";

    fn apply_overrides(&self, c: &mut Config) {
        self.rig.apply(&mut c.tire, &mut c.rig);
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let (_, s) = run_reduced(
            ctx,
            &c.tire,
            c.speeds_kmh.len(),
            "speed sweep",
            |red, bar| {
                // each speed's files are written as soon as it is done (a failed sweep keeps
                // them); a write error stops the sweep and is reported as such
                let mut kept: Option<StudyError> = None;
                let result = run_sweep(red, c, bar, &mut |v, r| {
                    crate::cleat::write_outputs(ctx, r, &format!("v{v:03.0}_"), true, &[]).map_err(
                        |e| {
                            let reason = format!("{e:?}");
                            kept = Some(e);
                            TireError::Simulation { time: 0.0, reason }
                        },
                    )
                });
                if let Some(e) = kept {
                    return Err(e);
                }
                // the speeds done so far keep their files and go into the failed summary
                result.map_err(|f| match rig_err(f.error) {
                    StudyError::Numerical { message, .. } => StudyError::Numerical {
                        message: format!("at {} km/h: {message}", f.speed_kmh),
                        partial: serde_json::to_value(&f.runs).ok(),
                    },
                    other => other,
                })
            },
        )?;
        ctx.out
            .write_csv("waterfall.csv", &WATERFALL_COLUMNS, &s.waterfall)?;
        // the speed x frequency matrices (rows: speeds, columns: frequencies)
        let header = matrix_header(&s.freq_hz);
        for (name, m) in [("fy", &s.fy_matrix), ("fx", &s.fx_matrix)] {
            ctx.out.write_csv(
                &format!("{name}_matrix.csv"),
                &header,
                c.speeds_kmh.iter().zip(m.iter()).map(|(v, row)| {
                    std::iter::once(*v)
                        .chain(row.iter().copied())
                        .collect::<Vec<f64>>()
                }),
            )?;
            let label = if name == "fy" {
                "vertical Fy"
            } else {
                "longitudinal Fx"
            };
            SpectrumMap {
                title: format!("Spectrum of the {label} spindle force against speed"),
                speeds: &c.speeds_kmh,
                freqs: &s.freq_hz,
                amp: m,
            }
            .save(&ctx.out.path(&format!("{name}_map")))?;
        }
        let summary = s.summary;
        let pts = |a: &[f64]| {
            c.speeds_kmh
                .iter()
                .copied()
                .zip(a.iter().copied())
                .collect()
        };
        LinePlot::new(
            "Peak spectral amplitude against speed",
            "v [km/h]",
            "amplitude [N]",
        )
        .with(Series::line("Fy", pts(&summary.fy_peak_amplitude_n)))
        .with(Series::line("Fx", pts(&summary.fx_peak_amplitude_n)))
        .save(&ctx.out.path("peak_vs_speed"))?;
        Ok(summary)
    }
}
