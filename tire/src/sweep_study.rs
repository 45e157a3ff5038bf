//! The speed sweep of the cleat test (`flowmbd-tire sweep`, `flowmbd.tire.sweep`; Ribaric
//! Figs. 8-7, 8-8 on the drum, 8-14 on the flat road): the cleat test of §8.3 at every speed,
//! the peak spectral amplitudes against speed, their local minima (the speed dips) and the
//! spectra as a speed × frequency table. Configuration, summary and the tables of the CSV
//! files live here so that the CLI and the Python package return the same numbers.

use crate::dips::local_minima;
use crate::error::TireError;
use crate::reduced::ReducedTire;
use crate::rig::{RigConfig, RigResult, run_cleat};
use crate::source::TireSource;
use crate::spectrum::{PEAK_BAND_HZ, Spectrum, spectrum_grid};
use crate::study::{CleatSummary, summarize, validate_rig};
use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// Configuration of the speed sweep.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct SweepStudyConfig {
    /// The tire.
    pub tire: TireSource,
    /// The rig (its speed is replaced by each sweep speed).
    pub rig: RigConfig,
    /// Speeds \[km/h\].
    pub speeds_kmh: Vec<f64>,
}

impl Default for SweepStudyConfig {
    fn default() -> Self {
        Self {
            tire: TireSource::default(),
            rig: RigConfig::default(),
            speeds_kmh: (2..=10).map(|k| 10.0 * k as f64).collect(),
        }
    }
}

impl mbd_core::config::PartialRules for SweepStudyConfig {}

impl Validate for SweepStudyConfig {
    /// The tire, the rig ([`validate_rig`]) and at least one positive, finite speed.
    fn validate(&self) -> Result<(), InvalidField> {
        self.tire.validate_within("tire")?;
        validate_rig(&self.rig)?;
        if self.speeds_kmh.is_empty() {
            return Err(InvalidField::new("speeds_kmh", "is empty"));
        }
        for (i, v) in self.speeds_kmh.iter().enumerate() {
            if !(*v > 0.0 && v.is_finite()) {
                return Err(InvalidField::new(
                    format!("speeds_kmh[{i}]"),
                    "must be positive",
                ));
            }
        }
        Ok(())
    }
}

/// Summary of the speed sweep (`summary.json`).
#[derive(Debug, Serialize)]
pub struct SweepSummary {
    /// Per-speed summaries ([`summarize`]).
    pub runs: Vec<CleatSummary>,
    /// Peak vertical amplitude per speed \[N\].
    pub fy_peak_amplitude_n: Vec<f64>,
    /// Peak longitudinal amplitude per speed \[N\].
    pub fx_peak_amplitude_n: Vec<f64>,
    /// Frequency of the vertical peak per speed \[Hz\], interpolated between the bins
    /// ([`Spectrum::interpolated_peak`]; the `fy_peak_hz` of `runs`).
    pub fy_peak_hz: Vec<f64>,
    /// Frequency resolution of each speed's record \[Hz\] (bin spacing `1/(N Δt)`; the
    /// `peak_resolution_hz` of `runs`).
    pub peak_resolution_hz: Vec<f64>,
    /// Whether the vertical amplitude against speed is non-monotonic.
    pub fy_amplitude_non_monotonic: bool,
    /// Speeds at which the vertical peak amplitude has a local minimum (a dip; Ribaric: 40–50
    /// km/h on the drum, 45–55 km/h on the road) \[km/h\].
    pub fy_amplitude_dips_kmh: Vec<f64>,
    /// What the numbers mean ([`SWEEP_MEANING`]).
    pub meaning: String,
}

/// The sweep's "what the numbers mean" paragraph (`meaning` in `summary.json`).
pub const SWEEP_MEANING: &str = "The cleat test at every speed of speeds_kmh (Ribaric Figs. 8-7, 8-8, 8-14): per \
     speed the summary of the cleat study (runs), the largest spectral amplitudes of F_y \
     and F_x [N] and the frequency of the F_y peak [Hz] (interpolated between the bins \
     of the record's spectrum, whose spacing is peak_resolution_hz). fy_matrix.csv and \
     fx_matrix.csv hold the spectra as a speed x frequency table (every run resampled \
     onto the first run's frequency grid) behind the contour and waterfall plots. fy_amplitude_dips_kmh \
     lists the speeds at which the vertical amplitude has a local minimum (Ribaric: 40-50 \
     km/h on the drum), where the cleat excitation and the tire's vertical mode \
     interfere.";

/// Highest frequency of the speed × frequency maps and the waterfall table \[Hz\].
pub const MAP_MAX_HZ: f64 = 300.0;

/// Columns of `waterfall.csv` ([`SweepResult::waterfall`]).
pub const WATERFALL_COLUMNS: [&str; 4] = ["speed_km_per_h", "f_Hz", "fx_amp_N", "fy_amp_N"];

/// The outcome of the sweep: the summary and the tables behind the CSV files and maps.
#[derive(Debug)]
pub struct SweepResult {
    /// The summary.
    pub summary: SweepSummary,
    /// Rows of `waterfall.csv` ([`WATERFALL_COLUMNS`]): every run's own spectrum bins up to
    /// [`MAP_MAX_HZ`] (speed \[km/h\], f \[Hz\], |F_x|, |F_y| \[N\]).
    pub waterfall: Vec<[f64; 4]>,
    /// The common frequencies of the matrices \[Hz\] (the first run's bins up to
    /// [`MAP_MAX_HZ`], [`spectrum_grid`]).
    pub freq_hz: Vec<f64>,
    /// `|F_x|` per speed (rows) and frequency (columns) \[N\].
    pub fx_matrix: Vec<Vec<f64>>,
    /// `|F_y|` per speed (rows) and frequency (columns) \[N\].
    pub fy_matrix: Vec<Vec<f64>>,
}

/// A sweep that failed at `speed_kmh`, with the summaries of the speeds done before.
#[derive(Debug)]
pub struct SweepFailure {
    /// The speed that failed \[km/h\].
    pub speed_kmh: f64,
    /// Its error.
    pub error: TireError,
    /// The runs done before it.
    pub runs: Vec<CleatSummary>,
}

/// Run the cleat test ([`run_cleat`]) at every speed of `c.speeds_kmh` on the reduced tire
/// `red`; `progress` gets the fraction done (0–1) and `on_run` every finished run with its
/// speed \[km/h\] (e.g. to write its files; an error stops the sweep). The vertical peak is
/// interpolated in [`PEAK_BAND_HZ`]; the dips are the interior local minima of the vertical
/// peak amplitude against speed ([`local_minima`]).
pub fn run_sweep(
    red: &ReducedTire, c: &SweepStudyConfig, progress: &mut dyn FnMut(f64),
    on_run: &mut dyn FnMut(f64, &RigResult) -> Result<(), TireError>,
) -> Result<SweepResult, Box<SweepFailure>> {
    let n = c.speeds_kmh.len().max(1) as f64;
    let mut runs = Vec::new();
    let (mut ay, mut ax) = (Vec::new(), Vec::new());
    let mut waterfall = Vec::new();
    let mut fpk = Vec::new();
    let mut resolution = Vec::new();
    let mut spectra: Vec<(Spectrum, Spectrum)> = Vec::new();
    for (k, &v) in c.speeds_kmh.iter().enumerate() {
        let mut rig = c.rig.clone();
        rig.speed_kmh = v;
        let done = run_cleat(red, &rig, &mut |f| progress((k as f64 + f) / n))
            .and_then(|r| on_run(v, &r).map(|()| r));
        let r = match done {
            Ok(r) => r,
            Err(error) => {
                return Err(Box::new(SweepFailure {
                    speed_kmh: v,
                    error,
                    runs,
                }));
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
                waterfall.push([v, sy.freq_hz[i], sx.amplitude[i], sy.amplitude[i]]);
            }
        }
        runs.push(summarize(&r));
        spectra.push((sx, sy));
    }
    // the speed × frequency matrices on the first run's frequency grid, every run's spectrum
    // resampled onto it (records differ by a sample between speeds, so their bins differ:
    // `Spectrum::resample`)
    let mx = spectrum_grid(
        &spectra.iter().map(|s| &s.0).collect::<Vec<_>>(),
        MAP_MAX_HZ,
    );
    let my = spectrum_grid(
        &spectra.iter().map(|s| &s.1).collect::<Vec<_>>(),
        MAP_MAX_HZ,
    );
    let incr = ay.windows(2).any(|w| w[1] > w[0]);
    let decr = ay.windows(2).any(|w| w[1] < w[0]);
    let dips = local_minima(&c.speeds_kmh, &ay);
    Ok(SweepResult {
        summary: SweepSummary {
            runs,
            fy_peak_amplitude_n: ay,
            fx_peak_amplitude_n: ax,
            fy_peak_hz: fpk,
            peak_resolution_hz: resolution,
            fy_amplitude_non_monotonic: incr && decr,
            fy_amplitude_dips_kmh: dips,
            meaning: SWEEP_MEANING.to_string(),
        },
        waterfall,
        freq_hz: my.freq_hz,
        fx_matrix: mx.rows,
        fy_matrix: my.rows,
    })
}

/// The header of `fy_matrix.csv` and `fx_matrix.csv`: `speed_km_per_h`, then
/// `f<frequency with 3 decimals>Hz_amp_N` per frequency of `freq_hz`.
pub fn matrix_header(freq_hz: &[f64]) -> Vec<String> {
    std::iter::once("speed_km_per_h".to_string())
        .chain(freq_hz.iter().map(|f| format!("f{f:.3}Hz_amp_N")))
        .collect()
}
