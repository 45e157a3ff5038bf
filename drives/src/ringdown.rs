//! Free ring-down of a belt drive about its settled state (issue 36 item 2: the design study's
//! rotational modes, [`crate::fead_design::modes`], against the time simulation).
//!
//! The drive runs on the shared time loop ([`crate::BeltSimulation`], generalized-α) to its
//! settled state under its own signals; one loaded pulley then receives a short torque pulse on
//! top of its load torque (its signal the C¹ schedule through `Q` at the pulse's start,
//! `Q + P` at its middle and `Q` at its end, [`belt::Signal::schedule`]), and the free vibration that follows is recorded: the
//! pulleys' speeds and the tensioner arm's angle. Its frequencies are the peaks of the
//! Hann-windowed discrete Fourier amplitude ([`spectrum_peaks`]) of a recorded signal: for a
//! lightly damped mode (ζ of a few per cent) the peak lies at the damped frequency
//! `ω_d = ω √(1 − ζ²)`, within `ζ²/2` of the natural one, on a grid of the caller's step.

use belt::{BeltModel, Motion, Signal};
use mbd_core::MbdError;
use mbd_core::integrators::AlphaConfig;
use mbd_core::validate::{InvalidField, check};

use crate::BeltSimulation;

/// Most recorded steps of a ring-down (the record's length over the step size).
pub const MAX_RING_DOWN_STEPS: usize = 10_000_000;

/// Most frequencies of a [`spectrum_peaks`] grid.
pub const MAX_SPECTRUM_POINTS: usize = 1_000_000;

/// The pulse and the record of a ring-down (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RingDownSettings {
    /// The loaded pulley that receives the pulse (travel order).
    pub pulley: usize,
    /// Time over which its load torque rises from 0 to its final value \[s\] (the pulley's
    /// signal is replaced by this ramp, the pulse and the hold).
    pub ramp: f64,
    /// Time from the end of the ramp to the pulse \[s\]: the drive settles.
    pub settle: f64,
    /// Peak torque of the pulse added to the load torque \[N m\].
    pub pulse_torque: f64,
    /// Duration of the pulse \[s\].
    pub pulse_duration: f64,
    /// Length of the record after the pulse \[s\].
    pub record: f64,
}

/// A recorded ring-down.
#[derive(Debug, Clone, PartialEq)]
pub struct RingDown {
    /// Sample times \[s\] (every step after the pulse).
    pub times: Vec<f64>,
    /// Speed of every pulley at every sample \[rad/s\] (`pulley_speeds[k][i]`).
    pub pulley_speeds: Vec<Vec<f64>>,
    /// Tensioner arm angle at every sample \[rad\] (empty without a tensioner).
    pub arm_angle: Vec<f64>,
}

/// What can stop a ring-down.
#[derive(Debug, thiserror::Error)]
pub enum RingDownError {
    /// The settings do not fit the drive.
    #[error(transparent)]
    Invalid(#[from] InvalidField),
    /// The time loop failed.
    #[error("ring-down: {0}")]
    Step(#[from] MbdError),
}

/// Run the ring-down of `model` with the generalized-α settings `alpha` (module
/// documentation).
///
/// # Errors
/// [`RingDownError::Invalid`]: `settings.pulley` is not a loaded pulley of the drive, a time
/// is not positive (`settle` may be 0) or the record exceeds [`MAX_RING_DOWN_STEPS`] steps;
/// [`RingDownError::Step`]: the stepper's failure.
pub fn ring_down<M: BeltModel>(
    mut model: M, alpha: AlphaConfig, settings: &RingDownSettings,
) -> Result<RingDown, RingDownError> {
    let s = settings;
    let torque = match model.drive().pulleys().get(s.pulley).map(|p| &p.motion) {
        Some(Motion::Load { torque, .. }) => torque.final_value(),
        _ => {
            return Err(InvalidField::new(
                "pulley",
                format!("pulley {} is not a loaded pulley of the drive", s.pulley),
            )
            .into());
        }
    };
    check::positive("ramp", s.ramp, "s")?;
    check::non_negative("settle", s.settle, "s")?;
    check::finite("pulse_torque", s.pulse_torque)?;
    check::positive("pulse_duration", s.pulse_duration, "s")?;
    check::positive("record", s.record, "s")?;
    check::positive("alpha.h", alpha.h, "s")?;
    let steps = (s.ramp + s.settle + 2.0 * s.pulse_duration + s.record) / alpha.h;
    if steps > MAX_RING_DOWN_STEPS as f64 {
        return Err(InvalidField::new(
            "record",
            format!(
                "{steps:.3e} steps of {} s: at most {MAX_RING_DOWN_STEPS}",
                alpha.h
            ),
        )
        .into());
    }
    let t1 = s.ramp + s.settle;
    let d = s.pulse_duration;
    model.set_signal(
        s.pulley,
        Signal::schedule(vec![
            (0.0, 0.0),
            (s.ramp, torque),
            (t1, torque),
            (t1 + 0.5 * d, torque + s.pulse_torque),
            (t1 + d, torque),
        ]),
    )?;
    let n = model.drive().pulleys().len();
    let mut sim: BeltSimulation<M> = BeltSimulation::new(model, alpha)?;
    let mut out = RingDown {
        times: Vec::new(),
        pulley_speeds: vec![Vec::new(); n],
        arm_angle: Vec::new(),
    };
    let start = t1 + d;
    while sim.state().t < start + s.record {
        sim.step()?;
        let st = sim.state();
        if st.t > start {
            out.times.push(st.t);
            for (k, y) in out.pulley_speeds.iter_mut().enumerate() {
                y.push(sim.model().pulley_speed(k, st.t, &st.v));
            }
            if let Some(a) = sim.model().arm_angle(&st.q) {
                out.arm_angle.push(a);
            }
        }
    }
    Ok(out)
}

/// Local maxima of the Hann-windowed discrete Fourier amplitude of `y` sampled at `times`
/// (mean removed) on the frequency grid `band[0], band[0] + step, … ≤ band[1]` \[Hz\], as
/// `(frequency [Hz], amplitude over the largest)`, those above `floor` of the largest, in
/// ascending frequency (module documentation). Empty for fewer than three samples or grid
/// points, a grid of [`MAX_SPECTRUM_POINTS`] points or more, or a constant signal.
pub fn spectrum_peaks(
    times: &[f64], y: &[f64], band: [f64; 2], step: f64, floor: f64,
) -> Vec<(f64, f64)> {
    let n = times.len().min(y.len());
    let grid = (band[1] - band[0]) / step;
    let valid = step > 0.0 && band[1] > band[0] && grid.is_finite();
    if n < 3 || !valid || grid >= MAX_SPECTRUM_POINTS as f64 {
        return Vec::new();
    }
    let mean = y[..n].iter().sum::<f64>() / n as f64;
    let tau = 2.0 * std::f64::consts::PI;
    let points = grid.floor() as usize + 1;
    let rows: Vec<(f64, f64)> = (0..points)
        .map(|i| {
            let f = band[0] + i as f64 * step;
            let w = tau * f;
            let (mut c, mut s) = (0.0, 0.0);
            for i in 0..n {
                let hann = 0.5 - 0.5 * (tau * i as f64 / n as f64).cos();
                let v = hann * (y[i] - mean);
                c += v * (w * times[i]).cos();
                s += v * (w * times[i]).sin();
            }
            (f, c.hypot(s))
        })
        .collect();
    let top = rows.iter().map(|r| r.1).fold(0.0, f64::max);
    if rows.len() < 3 || top.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Vec::new();
    }
    (1..rows.len() - 1)
        .filter(|&i| rows[i].1 > rows[i - 1].1 && rows[i].1 >= rows[i + 1].1)
        .filter(|&i| rows[i].1 > floor * top)
        .map(|i| (rows[i].0, rows[i].1 / top))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    // Closed form: a decaying sine e^{−ζωt} sin(ω_d t) of 45 Hz, ζ = 0.02, sampled at 4 kHz
    // over 0.4 s: the windowed spectrum peaks at ω_d/2π = 45 √(1 − ζ²) Hz within the 0.05 Hz
    // grid (and half a bin of the Hann window's bias, far below it here); a second, weaker
    // sine of 120 Hz is the second peak.
    #[test]
    fn spectrum_peak_of_a_damped_sine_is_its_frequency() {
        let (f, zeta) = (45.0, 0.02);
        let w = 2.0 * std::f64::consts::PI * f;
        let wd = w * (1.0f64 - zeta * zeta).sqrt();
        let times: Vec<f64> = (0..1600).map(|i| 0.1 + i as f64 / 4000.0).collect();
        let y: Vec<f64> = times
            .iter()
            .map(|&t| {
                let s = t - 0.1;
                (-zeta * w * s).exp() * (wd * s).sin()
                    + 0.3 * (2.0 * std::f64::consts::PI * 120.0 * s).sin()
            })
            .collect();
        let peaks = spectrum_peaks(&times, &y, [10.0, 200.0], 0.05, 0.05);
        assert_eq!(peaks.len(), 2, "{peaks:?}");
        assert!(
            (peaks[0].0 - wd / (2.0 * std::f64::consts::PI)).abs() <= 0.05,
            "{peaks:?}"
        );
        assert!((peaks[1].0 - 120.0).abs() <= 0.05, "{peaks:?}");
        assert!(spectrum_peaks(&times, &vec![1.0; 1600], [10.0, 200.0], 0.05, 0.05).is_empty());
    }
}
