//! Amplitude spectra of the spindle forces (rustfft), Ribaric Fig. 8-5.

use rustfft::FftPlanner;
use rustfft::num_complex::Complex;
use serde::Serialize;

/// Frequency band \[Hz\] in which the cleat test's spectral peaks (`fx_peak_hz`,
/// `fy_peak_hz`) are sought: above the rolling and drum-revolution orders, below the
/// reduced tire's highest resolved modes (Ribaric §8.3, Figs. 8-5 to 8-8: lines at 40-250 Hz).
pub const PEAK_BAND_HZ: [f64; 2] = [10.0, 500.0];

/// One-sided amplitude spectrum of a uniformly sampled signal.
#[derive(Debug, Clone, Serialize)]
pub struct Spectrum {
    /// Frequencies \[Hz\].
    pub freq_hz: Vec<f64>,
    /// Amplitudes (same unit as the signal; a sine of amplitude A shows as ≈ A).
    pub amplitude: Vec<f64>,
}

/// Amplitude spectrum of `x` sampled every `dt` \[s\]: mean removed, Hann window, amplitude
/// corrected for the window's coherent gain (0.5).
pub fn amplitude_spectrum(x: &[f64], dt: f64) -> Spectrum {
    let n = x.len();
    if n < 2 || dt.is_nan() || dt <= 0.0 {
        return Spectrum {
            freq_hz: Vec::new(),
            amplitude: Vec::new(),
        };
    }
    let mean = x.iter().sum::<f64>() / n as f64;
    let mut buf: Vec<Complex<f64>> = x
        .iter()
        .enumerate()
        .map(|(i, &v)| {
            let w = 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / (n - 1) as f64).cos();
            Complex::new((v - mean) * w, 0.0)
        })
        .collect();
    FftPlanner::new().plan_fft_forward(n).process(&mut buf);
    let half = n / 2 + 1;
    let scale = 2.0 / (0.5 * n as f64);
    Spectrum {
        freq_hz: (0..half).map(|k| k as f64 / (n as f64 * dt)).collect(),
        amplitude: (0..half).map(|k| buf[k].norm() * scale).collect(),
    }
}

/// Half-width \[Hz\] of the band around a spectral line over which [`Spectrum::band_rms`] sums
/// for the cleat summary's `fy_band_rms_n` and `fx_band_rms_n`: wide enough for the
/// line's Hann main lobe (±2 bins at the 3.3 Hz resolution of a 0.3 s record) and for the
/// line moving by a bin or two between runs, narrow enough to exclude the next lines
/// (BENCHMARKS.md: Fy 73–77 Hz, Fx 23 and 90 Hz).
pub const LINE_BAND_HZ: f64 = 10.0;

impl Spectrum {
    /// RMS \[signal unit\] of the lines within `[f_lo, f_hi]` \[Hz\] (Parseval over the band):
    /// `√(Σ aₖ² / 3)`, each bin's amplitude `aₖ` a sine of rms `aₖ/√2` and the Hann window's
    /// equivalent noise bandwidth of 1.5 bins removed, so that a sine of amplitude `A` whose
    /// main lobe lies in the band gives `A/√2`. It sums the energy of a line spread over
    /// several bins (the main lobe, a line between two bins), so it compares runs more steadily
    /// than the peak bin. (The converged-step tables of BENCHMARKS.md before issue #16's
    /// real-time work gave `√(Σ aₖ²/2)`, √1.5 times this.) 0 for an empty band.
    pub fn band_rms(&self, f_lo: f64, f_hi: f64) -> f64 {
        let s: f64 = self
            .freq_hz
            .iter()
            .zip(&self.amplitude)
            .filter(|(f, _)| **f >= f_lo && **f <= f_hi)
            .map(|(_, a)| a * a)
            .sum();
        (s / 3.0).sqrt()
    }

    /// Frequency of the largest bin within `[f_lo, f_hi]` \[Hz\] and its amplitude (`None` if
    /// empty): the raw bin, [`Spectrum::resolution_hz`] coarse ([`Spectrum::interpolated_peak`]
    /// locates the line between the bins).
    pub fn peak(&self, f_lo: f64, f_hi: f64) -> Option<(f64, f64)> {
        self.peak_bin(f_lo, f_hi)
            .map(|k| (self.freq_hz[k], self.amplitude[k]))
    }

    /// Index of the largest bin within `[f_lo, f_hi]` \[Hz\].
    fn peak_bin(&self, f_lo: f64, f_hi: f64) -> Option<usize> {
        (0..self.freq_hz.len().min(self.amplitude.len()))
            .filter(|&k| self.freq_hz[k] >= f_lo && self.freq_hz[k] <= f_hi)
            .max_by(|&a, &b| self.amplitude[a].total_cmp(&self.amplitude[b]))
    }

    /// Bin spacing \[Hz\]: the record's frequency resolution `1/(N Δt)` (no zero padding; NaN
    /// for a spectrum of fewer than two bins).
    pub fn resolution_hz(&self) -> f64 {
        self.freq_hz.get(1).copied().unwrap_or(f64::NAN)
    }

    /// Frequency \[Hz\] of the largest line within `[f_lo, f_hi]` \[Hz\] interpolated between
    /// the bins (the peak bin [`Spectrum::peak`] moved by
    /// [`flowing::spectrum::peak_offset`], Gaussian interpolation of the three bins around
    /// it: Gasior & Gonzalez 2004), and the peak bin's amplitude (`None` if the band is empty).
    /// A line between two bins is found to a few hundredths of [`Spectrum::resolution_hz`]
    /// instead of up to half of it, so a sweep of it over speed does not jump bin by bin.
    pub fn interpolated_peak(&self, f_lo: f64, f_hi: f64) -> Option<(f64, f64)> {
        let k = self.peak_bin(f_lo, f_hi)?;
        let delta = flowing::spectrum::peak_offset(&self.amplitude, k);
        Some((
            self.freq_hz[k] + delta * self.resolution_hz(),
            self.amplitude[k],
        ))
    }
}

impl Spectrum {
    /// The amplitude spectrum on the frequencies `grid` \[Hz\]: linear interpolation between
    /// the two bins around each frequency (a grid frequency on a bin takes that bin's value
    /// exactly), 0 outside the spectrum's range.
    ///
    /// Spectra of records of different length have different bins (`k/(N h)`): a sweep's runs
    /// differ by a sample when the hit falls between steps differently, and 1001 samples at
    /// h = 0.2 ms put the bins 4.995 Hz apart instead of 5 Hz. Looking the other runs' bins up
    /// on the first run's grid by equality found only 0 Hz and wrote zero rows into the
    /// speed × frequency map (issue 20); resampling puts every run on the common grid.
    pub fn resample(&self, grid: &[f64]) -> Vec<f64> {
        let f = &self.freq_hz;
        grid.iter()
            .map(|&x| {
                // first bin at or above x
                let j = f.partition_point(|&g| g < x);
                match (j, f.get(j)) {
                    (_, Some(&g)) if g == x => self.amplitude[j],
                    (0, _) | (_, None) => 0.0,
                    (j, Some(&g)) => {
                        let (g0, a0, a1) = (f[j - 1], self.amplitude[j - 1], self.amplitude[j]);
                        a0 + (a1 - a0) * (x - g0) / (g - g0)
                    }
                }
            })
            .collect()
    }
}

/// Spectra of several runs on one frequency grid (rows: runs, columns: frequencies), the table
/// behind the speed × frequency contour and waterfall maps (Ribaric Figs. 8-7, 8-8).
#[derive(Debug, Clone, Serialize)]
pub struct SpectrumGrid {
    /// The common frequencies \[Hz\]: the bins of the first spectrum up to `f_max`.
    pub freq_hz: Vec<f64>,
    /// One row per spectrum: its amplitudes resampled on `freq_hz` ([`Spectrum::resample`]).
    pub rows: Vec<Vec<f64>>,
}

/// The spectra on the bins of the first one up to `f_max` \[Hz\] ([`SpectrumGrid`]).
pub fn spectrum_grid(spectra: &[&Spectrum], f_max: f64) -> SpectrumGrid {
    let freq_hz: Vec<f64> = spectra
        .first()
        .map(|s| s.freq_hz.iter().copied().filter(|f| *f <= f_max).collect())
        .unwrap_or_default();
    let rows = spectra.iter().map(|s| s.resample(&freq_hz)).collect();
    SpectrumGrid { freq_hz, rows }
}

/// Root mean square of the fluctuation of `x` about its mean.
pub fn rms_fluctuation(x: &[f64]) -> f64 {
    if x.is_empty() {
        return 0.0;
    }
    let n = x.len() as f64;
    let m = x.iter().sum::<f64>() / n;
    (x.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / n).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    // Reference: a sine of amplitude A has rms A/√2 (analytical), on a bin and between two
    // bins (where the peak bin alone loses up to 15 %, Harris 1978, but the band keeps the
    // line's energy); a second line outside the band does not enter.
    #[test]
    fn band_rms_of_a_sine_is_its_rms() {
        let h = 5e-5;
        let n = 6000; // 0.3 s: 3.33 Hz bins
        for f in [75.0, 76.0 + 2.0 / 3.0, 75.0 + 5.0 / 3.0] {
            let a = 800.0;
            let x: Vec<f64> = (0..n)
                .map(|i| {
                    let t = i as f64 * h;
                    a * (2.0 * PI * f * t).sin() + 300.0 * (2.0 * PI * 23.3 * t).cos()
                })
                .collect();
            let s = amplitude_spectrum(&x, h);
            let rms = s.band_rms(f - LINE_BAND_HZ, f + LINE_BAND_HZ);
            let want = a / 2f64.sqrt();
            assert!(
                (rms - want).abs() < 0.01 * want,
                "{f} Hz: band rms {rms} vs {want}"
            );
        }
        assert_eq!(
            amplitude_spectrum(&[1.0; 10], h).band_rms(600.0, 700.0),
            0.0
        );
    }

    // Reference: a pure sinusoid's frequency (closed form: the one it was sampled at), placed
    // between the bins of a 0.3 s record (3.33 Hz resolution) at 74.9 Hz and 76.1 Hz, where the
    // raw peak bin is off by 1.57 Hz and 0.57 Hz; the interpolated peak must be within 0.03 bin
    // (0.1 Hz), and the resolution the record's 1/(N h).
    #[test]
    fn interpolated_peak_finds_a_line_between_bins() {
        let h = 5e-5;
        let n = 6000;
        for f in [74.9, 76.1, 75.0] {
            let x: Vec<f64> = (0..n)
                .map(|i| 1344.0 * (2.0 * PI * f * i as f64 * h + 1.1).sin() + 25_000.0)
                .collect();
            let s = amplitude_spectrum(&x, h);
            let df = s.resolution_hz();
            assert!((df - 1.0 / (n as f64 * h)).abs() < 1e-12, "{df}");
            let (fi, ai) = s.interpolated_peak(10.0, 500.0).unwrap();
            let (fb, ab) = s.peak(10.0, 500.0).unwrap();
            assert_eq!(ai, ab);
            assert!(
                (fi - f).abs() < 0.03 * df,
                "{f} Hz: interpolated {fi}, bin {fb}"
            );
            assert!((fi - fb).abs() <= 0.5 * df);
        }
        assert_eq!(
            amplitude_spectrum(&[1.0; 10], h).interpolated_peak(600.0, 700.0),
            None
        );
    }

    // issue 20 reproducer: 1000 and 1001 samples at h = 0.2 ms have bins 5 Hz and 4.995 Hz
    // apart; a 74.9 Hz sine of amplitude 1344 N (the 90 km/h line) sampled 1001 times must
    // keep its peak near 74.9 Hz on the 5 Hz grid of the 1000-sample run. Reference: the
    // sine's own frequency and the Hann window's peak amplitude (coherent gain 0.5; the
    // off-bin loss of a Hann window is at most 1 − sinc-type 15 %, Harris 1978)
    #[test]
    fn resampling_keeps_an_off_grid_line_on_the_common_grid() {
        let h = 2e-4;
        let line = |n: usize, f: f64, a: f64| -> Vec<f64> {
            (0..n)
                .map(|i| a * (2.0 * PI * f * i as f64 * h).sin())
                .collect()
        };
        let s1000 = amplitude_spectrum(&line(1000, 60.0, 500.0), h);
        let s1001 = amplitude_spectrum(&line(1001, 74.9, 1344.0), h);
        assert!((s1000.freq_hz[1] - 5.0).abs() < 1e-9);
        assert!((s1001.freq_hz[1] - 4.995_004_995).abs() < 1e-6);
        let g = spectrum_grid(&[&s1000, &s1001], 300.0);
        assert_eq!(g.freq_hz.len(), 61);
        // the first row is the first spectrum itself, bin for bin
        assert_eq!(g.rows[0], s1000.amplitude[..61].to_vec());
        // the 90 km/h row: its peak where the run's own spectrum peaks, amplitude kept
        let (fp, ap) = s1001.peak(10.0, 300.0).unwrap();
        let row = &g.rows[1];
        let k = (0..row.len())
            .max_by(|&a, &b| row[a].total_cmp(&row[b]))
            .unwrap();
        assert!((g.freq_hz[k] - fp).abs() <= 5.0, "{} vs {fp}", g.freq_hz[k]);
        assert!((g.freq_hz[k] - 74.9).abs() <= 2.5, "{}", g.freq_hz[k]);
        assert!(
            row[k] > 0.85 * ap && row[k] <= ap * (1.0 + 1e-12),
            "{} vs {ap}",
            row[k]
        );
        // outside the spectrum's range: zero
        assert_eq!(s1001.resample(&[-1.0, 1e6]), vec![0.0, 0.0]);
    }
}
