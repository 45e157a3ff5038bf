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
    signal: &[f64],
    dt: f64,
    pad_factor: usize,
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
    /// in ascending frequency.
    pub fn peaks(&self, rel_threshold: f64) -> Vec<(f64, f64)> {
        let max = self.amplitudes.iter().cloned().fold(0.0, f64::max);
        let a = &self.amplitudes;
        (1..a.len().saturating_sub(1))
            .filter(|&k| a[k] > a[k - 1] && a[k] >= a[k + 1] && a[k] > rel_threshold * max)
            .map(|k| (self.frequencies[k], a[k]))
            .collect()
    }
}
