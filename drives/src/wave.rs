//! The measurements of the rotating vs non-rotating belt demonstration (Ribaric §6.2,
//! Fig. 6-3; the runs are [`flowing::belt::wave::wave_run`]): the span's vibration frequency
//! of each run and the drift speed of its deflection centroid, compared with the axially moving
//! string's frequency ratio `1 − v²/c²` (Ribaric §4.2).

use belt::{Drive, Layout};
use flowing::FlowError;
use flowing::belt::wave::{WaveConfig, WaveRun, dominant_frequency, wave_run, wave_speed};
use flowing::belt::{BeltMesh, BeltReduction, FlowingSettings};
use mbd_core::{InvalidField, Validate};
use serde::{Deserialize, Serialize};

/// The measurements of one run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RunSummary {
    /// Belt speed \[m/s\].
    pub belt_speed: f64,
    /// Dominant frequency of the mid-span deflection \[Hz\].
    pub frequency_hz: f64,
    /// Drift speed of the deflection centroid before the waves reach the pulleys \[m/s\].
    pub centroid_speed: f64,
}

/// Both runs compared.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveSummary {
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
    /// Time \[s\] until the faster wave front of the running belt, `v + c`, reaches the driven
    /// pulley from the edge of the bump: `(1/2 − b) L_s / (v + c)` (`b` the bump's half-width
    /// fraction, `L_s` the length of span 0); the centroid is measured before it.
    pub free_time: f64,
}

/// Least-squares slope of `y` against `t` (NaN with fewer than two samples).
pub fn slope(t: &[f64], y: &[f64]) -> f64 {
    let n = t.len() as f64;
    if t.len() < 2 {
        return f64::NAN;
    }
    let (mt, my) = (t.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = t.iter().zip(y).map(|(a, b)| (a - mt) * (b - my)).sum();
    let sxx: f64 = t.iter().map(|a| (a - mt) * (a - mt)).sum();
    sxy / sxx
}

/// Measure the runs `rest` and `running` of the drive `drive` with `settings`: the dominant
/// mid-span frequency searched between 0.2 and 2 times the string's fundamental `c/(2 L_s)` (`L_s` span 0's length),
/// and the centroid's drift speed until [`WaveSummary::free_time`].
pub fn summarize(
    drive: &Drive, settings: &WaveConfig, rest: &WaveRun, running: &WaveRun,
) -> WaveSummary {
    let cw = wave_speed(drive);
    let span = drive.spans().first().map_or(f64::NAN, |s| s.length);
    let t_free = (0.5 - settings.half_width) * span / (settings.belt_speed + cw);
    let f_string = cw / (2.0 * span);
    let measure = |r: &WaveRun| {
        let (t, x): (Vec<f64>, Vec<f64>) = r
            .times
            .iter()
            .zip(&r.centroid)
            .filter(|(t, _)| **t <= t_free)
            .map(|(t, x)| (*t, *x))
            .unzip();
        RunSummary {
            belt_speed: r.belt_speed,
            frequency_hz: dominant_frequency(&r.times, &r.midspan, 0.2 * f_string, 2.0 * f_string),
            centroid_speed: slope(&t, &x),
        }
    };
    let (a, b) = (measure(rest), measure(running));
    let v = settings.belt_speed;
    WaveSummary {
        wave_speed: cw,
        frequency_ratio: b.frequency_hz / a.frequency_hz,
        frequency_ratio_string: 1.0 - v * v / (cw * cw),
        rest: a,
        running: b,
        free_time: t_free,
    }
}

/// The `flowmbd-belt wave` study's configuration (SI units): the belt of Ribaric Fig. 6-3
/// deflected on one span and let go, at rest and running.
#[derive(Debug, Clone, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields)]
pub struct WaveStudyConfig {
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

impl Default for WaveStudyConfig {
    fn default() -> Self {
        Self {
            drive: crate::table_6_1::layout(),
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
impl mbd_core::config::PartialRules for WaveStudyConfig {
    const DROPPED_BY: &'static [(&'static str, &'static str)] = belt::PARTIAL_RULES;
}

impl Validate for WaveStudyConfig {
    fn validate(&self) -> Result<(), InvalidField> {
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
            return Err(InvalidField::new(
                "vtk_frames",
                format!(
                    "must lie in [1, wave.samples = {}] (one frame per recorded sample at most), got {}",
                    self.wave.samples, self.vtk_frames
                ),
            ));
        }
        if !(self.vtk_scale.is_finite() && self.vtk_scale > 0.0) {
            return Err(InvalidField::new("vtk_scale", "must be finite and > 0"));
        }
        Ok(())
    }
}

/// The study's summary (`summary.json`).
#[derive(Debug, Clone, Serialize)]
pub struct WaveStudySummary {
    /// Transverse wave speed `c = √(T0/ρA)` \[m/s\].
    pub wave_speed: f64,
    /// At rest.
    pub rest: RunSummary,
    /// Running.
    pub running: RunSummary,
    /// Measured frequency ratio running/rest.
    pub frequency_ratio: f64,
    /// Moving-string prediction `1 − v²/c²` (Ribaric §4.2).
    pub frequency_ratio_string: f64,
    /// Wall time \[s\].
    pub wall_time_s: f64,
    /// What the numbers mean ([`WAVE_MEANING`]).
    pub meaning: String,
}

/// What the summary's numbers mean.
pub const WAVE_MEANING: &str = "The flowing-material belt drive of Ribaric Fig. 6-3 with one \
span deflected and let go, once at rest and once running at the belt speed. wave_speed is the \
transverse wave speed c = sqrt(T0/(rho A)) [m/s]; rest and running hold the span's measured \
vibration in each case; frequency_ratio is the running span's lowest frequency over the resting \
one, and frequency_ratio_string the travelling-string prediction 1 - v^2/c^2 (Wickert and \
Mote): the axial motion lowers the span's frequencies, and the two ratios agree when the span \
behaves like a travelling string.";

/// Both runs of the study, their measurements and the undeformed loop.
#[derive(Debug, Clone)]
pub struct WaveStudy {
    /// The summary.
    pub summary: WaveStudySummary,
    /// [`WaveSummary::free_time`] \[s\].
    pub free_time: f64,
    /// The run at rest.
    pub rest: WaveRun,
    /// The running belt.
    pub running: WaveRun,
    /// Node positions of the undeformed loop \[m\] (the runs' shapes deflect from them).
    pub reference: Vec<[f64; 2]>,
}

/// Run the study `c` (validated): [`wave_run`] at rest and running, measured by
/// [`summarize`]; `progress` is called with the fraction done after each run.
pub fn run_wave_study(
    c: &WaveStudyConfig, mut progress: impl FnMut(f64),
) -> Result<WaveStudy, FlowError> {
    let start = std::time::Instant::now();
    let drive = c.drive.resolve().map_err(|e| e.within("drive"))?;
    let rest = wave_run(&drive, &c.flowing, &c.wave, false)?;
    progress(0.5);
    let running = wave_run(&drive, &c.flowing, &c.wave, true)?;
    progress(1.0);
    let m = summarize(&drive, &c.wave, &rest, &running);
    let reference = flowing::belt::BeltFe::new(&drive, &c.flowing.mesh)?.position;
    Ok(WaveStudy {
        summary: WaveStudySummary {
            wave_speed: m.wave_speed,
            frequency_ratio: m.frequency_ratio,
            frequency_ratio_string: m.frequency_ratio_string,
            rest: m.rest,
            running: m.running,
            wall_time_s: start.elapsed().as_secs_f64(),
            meaning: WAVE_MEANING.to_string(),
        },
        free_time: m.free_time,
        rest,
        running,
        reference,
    })
}

/// Columns of `wave.csv`.
pub const WAVE_CSV_HEADER: [&str; 5] = [
    "t_s",
    "midspan_rest_m",
    "midspan_running_m",
    "centroid_rest_m",
    "centroid_running_m",
];

/// Rows of `wave.csv` ([`WAVE_CSV_HEADER`]): per sample time the mid-span deflection and the
/// deflection centroid of both runs \[s, m\].
pub fn wave_csv_rows(rest: &WaveRun, running: &WaveRun) -> Vec<[f64; 5]> {
    (0..rest.times.len().min(running.times.len()))
        .map(|k| {
            [
                rest.times[k],
                rest.midspan[k],
                running.midspan[k],
                rest.centroid[k],
                running.centroid[k],
            ]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    // exact on a line y = 3 t − 1 (least squares)
    #[test]
    fn slope_of_a_line_is_exact() {
        let t = [0.0, 0.1, 0.25, 0.7];
        let y: Vec<f64> = t.iter().map(|t| 3.0 * t - 1.0).collect();
        assert!((slope(&t, &y) - 3.0).abs() < 1e-12);
        assert!(slope(&[1.0], &[2.0]).is_nan());
    }
}
