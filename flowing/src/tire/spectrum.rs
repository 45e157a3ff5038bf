//! Amplitude spectra of the spindle forces (rustfft), Ribaric Fig. 8-5.

use rustfft::FftPlanner;
use rustfft::num_complex::Complex;
use serde::Serialize;

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

impl Spectrum {
    /// Frequency of the largest amplitude within `[f_lo, f_hi]` \[Hz\] (`None` if empty).
    pub fn peak(&self, f_lo: f64, f_hi: f64) -> Option<(f64, f64)> {
        self.freq_hz
            .iter()
            .zip(&self.amplitude)
            .filter(|(f, _)| **f >= f_lo && **f <= f_hi)
            .max_by(|a, b| a.1.total_cmp(b.1))
            .map(|(f, a)| (*f, *a))
    }
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
