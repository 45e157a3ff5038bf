//! Amplitude spectra of sampled time histories (Ribaric Fig. 4-6 right: FFT of every modal
//! coordinate of the travelling string).

use crate::error::{FlowError, invalid};
use num_complex::Complex;
use rustfft::FftPlanner;

/// One-sided amplitude spectrum of a uniformly sampled signal.
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    /// Frequencies \[Hz\] (bin `k`: `k / (N dt)`).
    pub frequencies: Vec<f64>,
    /// Amplitudes (Hann-window corrected, units of the signal).
    pub amplitudes: Vec<f64>,
}

/// Hann-windowed, mean-removed, zero-padded (to `pad_factor · N`, rounded up to a power of two)
/// amplitude spectrum of `signal` sampled every `dt` seconds.
pub fn amplitude_spectrum(
    signal: &[f64], dt: f64, pad_factor: usize,
) -> Result<Spectrum, FlowError> {
    if signal.len() < 4 {
        return Err(invalid(
            "spectrum: signal",
            format!("{} samples are too few", signal.len()),
        ));
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(invalid(
            "spectrum: sampling step",
            format!("{dt} is not positive"),
        ));
    }
    let n = signal.len();
    let len = (n * pad_factor.max(1)).next_power_of_two();
    let mean = signal.iter().sum::<f64>() / n as f64;
    let w = |j: usize| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * j as f64 / (n - 1) as f64).cos();
    let wsum: f64 = (0..n).map(w).sum();
    let mut buf: Vec<Complex<f64>> = (0..len)
        .map(|j| {
            Complex::new(
                if j < n {
                    (signal[j] - mean) * w(j)
                } else {
                    0.0
                },
                0.0,
            )
        })
        .collect();
    FftPlanner::<f64>::new()
        .plan_fft_forward(len)
        .process(&mut buf);
    let half = len / 2 + 1;
    Ok(Spectrum {
        frequencies: (0..half).map(|k| k as f64 / (len as f64 * dt)).collect(),
        amplitudes: (0..half).map(|k| 2.0 * buf[k].norm() / wsum).collect(),
    })
}

impl Spectrum {
    /// Local maxima with amplitude above `rel_threshold · max`, as `(frequency, amplitude)`,
    /// in ascending frequency: the frequency interpolated between the bins around the maximum
    /// ([`peak_offset`]), the amplitude that of the largest bin.
    pub fn peaks(&self, rel_threshold: f64) -> Vec<(f64, f64)> {
        let max = self.amplitudes.iter().cloned().fold(0.0, f64::max);
        let a = &self.amplitudes;
        let df = self.frequencies.get(1).copied().unwrap_or(0.0);
        (1..a.len().saturating_sub(1))
            .filter(|&k| a[k] > a[k - 1] && a[k] >= a[k + 1] && a[k] > rel_threshold * max)
            .map(|k| (self.frequencies[k] + peak_offset(a, k) * df, a[k]))
            .collect()
    }
}

/// Offset δ \[bins\], in `[−½, ½]`, of the true maximum of a spectral line from its largest
/// bin `k`, so that the line's frequency is `f_k + δ Δf`: the vertex of the parabola through
/// the logarithms of the three amplitudes around the maximum, `δ = ½ (ln a₋ − ln a₊) / (ln a₋
/// − 2 ln a₀ + ln a₊)` (Gaussian interpolation: Gasior & Gonzalez, "Improving FFT frequency
/// measurement resolution by parabolic and Gaussian spectrum interpolation", AIP Conf. Proc.
/// 732, 2004, eq. (7); the log-parabola fits the main lobe of a Hann-windowed line closely,
/// with a bias of a few hundredths of a bin, where the raw bin is off by up to half a bin).
/// 0 when `k` is the first or last bin, a neighbour is not positive or the three do not form a
/// maximum (a flat top): the bin itself is then the best estimate.
pub fn peak_offset(amplitudes: &[f64], k: usize) -> f64 {
    if k == 0 || k + 1 >= amplitudes.len() {
        return 0.0;
    }
    let (a, b, c) = (amplitudes[k - 1], amplitudes[k], amplitudes[k + 1]);
    if !(a > 0.0 && b > 0.0 && c > 0.0) {
        return 0.0;
    }
    let (la, lb, lc) = (a.ln(), b.ln(), c.ln());
    let curvature = la - 2.0 * lb + lc;
    if curvature.is_nan() || curvature >= 0.0 {
        return 0.0;
    }
    (0.5 * (la - lc) / curvature).clamp(-0.5, 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    // Reference: a pure sinusoid's frequency is known in closed form (the one it was sampled
    // at); placed a quarter, a third and half a bin off the grid (where the raw bin is 0.25,
    // 0.33 and 0.5 bin away), the interpolated peak must land within 0.03 bin of it, with and
    // without zero padding.
    #[test]
    fn interpolated_peak_recovers_an_off_bin_sine() {
        let dt = 1e-3;
        let n = 1000; // 1 Hz record resolution
        for pad in [1, 4] {
            for f in [50.25, 50.0 + 1.0 / 3.0, 50.5, 123.7] {
                let x: Vec<f64> = (0..n)
                    .map(|i| 3.0 * (2.0 * PI * f * i as f64 * dt + 0.4).sin())
                    .collect();
                let s = amplitude_spectrum(&x, dt, pad).unwrap();
                let bin = s.frequencies[1];
                let p = s.peaks(0.5);
                assert_eq!(p.len(), 1, "{p:?}");
                let err = (p[0].0 - f).abs() / bin;
                assert!(
                    err < 0.03,
                    "pad {pad}, {f} Hz: peak {} Hz, {err} bins",
                    p[0].0
                );
            }
        }
        // two equal largest bins: the maximum midway between them (a symmetric lobe)
        assert_eq!(peak_offset(&[1.0, 2.0, 2.0], 1), 0.5);
        // degenerate neighbours: the bin itself
        assert_eq!(peak_offset(&[0.0, 2.0, 1.0], 1), 0.0);
        assert_eq!(peak_offset(&[2.0, 1.0], 0), 0.0);
        assert_eq!(peak_offset(&[1.0, 1.0, 1.0], 1), 0.0);
    }
}
