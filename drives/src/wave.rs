//! The measurements of the rotating vs non-rotating belt demonstration (Ribaric §6.2,
//! Fig. 6-3; the runs are [`flowing::belt::wave::wave_run`]): the span's vibration frequency
//! of each run and the drift speed of its deflection centroid, compared with the axially moving
//! string's frequency ratio `1 − v²/c²` (Ribaric §4.2).

use belt::Drive;
use flowing::belt::wave::{WaveConfig, WaveRun, dominant_frequency, wave_speed};
use serde::Serialize;

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
    drive: &Drive,
    settings: &WaveConfig,
    rest: &WaveRun,
    running: &WaveRun,
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
