//! `flowmbd-tire sweep`: the cleat test at 20, 30, ..., 100 km/h (Ribaric Figs. 8-7, 8-8 on the
//! drum, 8-14 on the flat road): peak spectral amplitudes against speed and the spectra as a
//! speed × frequency table for contour/waterfall plots.

use crate::cleat::{Summary as CleatSummary, summarize, validate_rig};
use crate::common::{RigFlags, TireSource, TireSourceExt, rig_err};
use crate::maps::SpectrumMap;
use flowmbd_cli::plot::{LinePlot, Series};
use flowmbd_cli::{CommonArgs, InputError, Study, StudyContext, StudyError, Validate, run_study};
use serde::{Deserialize, Serialize};
use std::process::ExitCode;
use tire::{PEAK_BAND_HZ, RigConfig, local_minima, run_cleat, spectrum_grid};

/// Command-line arguments.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Args {
    #[command(flatten)]
    common: CommonArgs,
    #[command(flatten)]
    rig: RigFlags,
}

/// Configuration.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct Config {
    /// The tire.
    pub tire: TireSource,
    /// The rig (its speed is replaced by each sweep speed).
    pub rig: RigConfig,
    /// Speeds \[km/h\].
    pub speeds_kmh: Vec<f64>,
}

impl Default for Config {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            rig: RigConfig::default(),
            speeds_kmh: (2..=10).map(|k| 10.0 * k as f64).collect(),
        }
    }
}

impl flowmbd_cli::PartialRules for Config {}

impl Validate for Config {
    fn validate(&self) -> Result<(), InputError> {
        self.tire.validate_within("tire")?;
        validate_rig(&self.rig)?;
        if self.speeds_kmh.is_empty() {
            return Err(InputError::new("speeds_kmh", "is empty"));
        }
        for (i, v) in self.speeds_kmh.iter().enumerate() {
            if !(*v > 0.0 && v.is_finite()) {
                return Err(InputError::new(
                    format!("speeds_kmh[{i}]"),
                    "must be positive",
                ));
            }
        }
        Ok(())
    }
}

/// Summary.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// Per-speed summaries.
    pub runs: Vec<CleatSummary>,
    /// Peak vertical amplitude per speed \[N\].
    pub fy_peak_amplitude_n: Vec<f64>,
    /// Peak longitudinal amplitude per speed \[N\].
    pub fx_peak_amplitude_n: Vec<f64>,
    /// Frequency of the vertical peak per speed \[Hz\], interpolated between the bins
    /// (`tire::Spectrum::interpolated_peak`; the `fy_peak_hz` of `runs`).
    pub fy_peak_hz: Vec<f64>,
    /// Frequency resolution of each speed's record \[Hz\] (bin spacing `1/(N Δt)`; the
    /// `peak_resolution_hz` of `runs`).
    pub peak_resolution_hz: Vec<f64>,
    /// Whether the vertical amplitude against speed is non-monotonic.
    pub fy_amplitude_non_monotonic: bool,
    /// Speeds at which the vertical peak amplitude has a local minimum (a dip; Ribaric: 40–50
    /// km/h on the drum, 45–55 km/h on the road) \[km/h\].
    pub fy_amplitude_dips_kmh: Vec<f64>,
}

/// Highest frequency of the speed × frequency maps and the waterfall table \[Hz\].
const MAP_MAX_HZ: f64 = 300.0;

struct Sweep {
    rig: RigFlags,
}

impl Study for Sweep {
    type Config = Config;
    type Summary = Summary;
    const APP: &'static str = "tire";
    const NAME: &'static str = "sweep";

    fn meaning(&self) -> &'static str {
        "The cleat test at every speed of speeds_kmh (Ribaric Figs. 8-7, 8-8, 8-14): per \
         speed the summary of the cleat study (runs), the largest spectral amplitudes of F_y \
         and F_x [N] and the frequency of the F_y peak [Hz] (interpolated between the bins \
         of the record's spectrum, whose spacing is peak_resolution_hz). fy_matrix.csv and \
         fx_matrix.csv hold the spectra as a speed x frequency table (every run resampled \
         onto the first run's frequency grid) behind the contour and waterfall plots. fy_amplitude_dips_kmh \
         lists the speeds at which the vertical amplitude has a local minimum (Ribaric: 40-50 \
         km/h on the drum), where the cleat excitation and the tire's vertical mode \
         interfere."
    }

    fn config_notes(&self, c: &Config) -> String {
        crate::common::import_notes(&c.tire)
    }

    fn apply_overrides(&self, c: &mut Config) {
        self.rig.apply(&mut c.tire, &mut c.rig);
    }

    fn run(&self, c: &Config, ctx: &mut StudyContext) -> Result<Summary, StudyError> {
        let red = c.tire.reduced(ctx.quiet)?;
        let bar = ctx.progress(c.speeds_kmh.len() as f64, "speed sweep");
        let mut runs = Vec::new();
        let (mut ay, mut ax) = (Vec::new(), Vec::new());
        let mut grid_rows = Vec::new();
        let mut fpk = Vec::new();
        let mut resolution = Vec::new();
        let mut spectra = Vec::new();
        for (k, &v) in c.speeds_kmh.iter().enumerate() {
            let mut rig = c.rig.clone();
            rig.speed_kmh = v;
            let r = match run_cleat(&red, &rig, &mut |f| bar.set(k as f64 + f)) {
                Ok(r) => r,
                // the speeds done so far keep their files and go into the failed summary
                Err(e) => {
                    return Err(match rig_err(e) {
                        StudyError::Numerical { message, .. } => StudyError::Numerical {
                            message: format!("at {v} km/h: {message}"),
                            partial: serde_json::to_value(&runs).ok(),
                        },
                        other => other,
                    });
                }
            };
            let (sx, sy) = r.spectra();
            let band = PEAK_BAND_HZ;
            let py = sy.interpolated_peak(band[0], band[1]).unwrap_or((0.0, 0.0));
            ay.push(py.1);
            fpk.push(py.0);
            resolution.push(sy.resolution_hz());
            ax.push(sx.peak(band[0], band[1]).map_or(0.0, |p| p.1));
            for i in 0..sy.freq_hz.len() {
                if sy.freq_hz[i] <= MAP_MAX_HZ {
                    grid_rows.push(vec![v, sy.freq_hz[i], sx.amplitude[i], sy.amplitude[i]]);
                }
            }
            crate::cleat::write_outputs(ctx, &r, &format!("v{v:03.0}_"), true, &[])?;
            runs.push(summarize(&r));
            spectra.push((sx, sy));
        }
        // the speed × frequency matrices (rows: speeds, columns: frequencies) on the first
        // run's frequency grid, every run's spectrum resampled onto it (records differ by a
        // sample between speeds, so their bins differ: `tire::Spectrum::resample`)
        let mx = spectrum_grid(
            &spectra.iter().map(|s| &s.0).collect::<Vec<_>>(),
            MAP_MAX_HZ,
        );
        let my = spectrum_grid(
            &spectra.iter().map(|s| &s.1).collect::<Vec<_>>(),
            MAP_MAX_HZ,
        );
        let freqs = my.freq_hz.clone();
        let (mx, my) = (mx.rows, my.rows);
        bar.finish();
        ctx.out.write_csv(
            "waterfall.csv",
            &["speed_km_per_h", "f_Hz", "fx_amp_N", "fy_amp_N"],
            grid_rows,
        )?;
        // the speed x frequency matrices (rows: speeds, columns: frequencies)
        let header: Vec<String> = std::iter::once("speed_km_per_h".to_string())
            .chain(freqs.iter().map(|f| format!("f{f:.3}Hz_amp_N")))
            .collect();
        let header: Vec<&str> = header.iter().map(String::as_str).collect();
        for (name, m) in [("fy", &my), ("fx", &mx)] {
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
                freqs: &freqs,
                amp: m,
            }
            .save(&ctx.out.path(&format!("{name}_map")))?;
        }
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
        .with(Series::line("Fy", pts(&ay)))
        .with(Series::line("Fx", pts(&ax)))
        .save(&ctx.out.path("peak_vs_speed"))?;
        let incr = ay.windows(2).any(|w| w[1] > w[0]);
        let decr = ay.windows(2).any(|w| w[1] < w[0]);
        let dips = local_minima(&c.speeds_kmh, &ay);
        Ok(Summary {
            runs,
            fy_peak_amplitude_n: ay,
            fx_peak_amplitude_n: ax,
            fy_peak_hz: fpk,
            peak_resolution_hz: resolution,
            fy_amplitude_non_monotonic: incr && decr,
            fy_amplitude_dips_kmh: dips,
        })
    }
}

/// Run the study.
pub fn run(args: &Args) -> ExitCode {
    run_study(
        &Sweep {
            rig: args.rig.clone(),
        },
        &args.common,
    )
}
