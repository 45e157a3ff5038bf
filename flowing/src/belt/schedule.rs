//! Time histories of prescribed quantities (driver speed, load torque).

use mbd_core::validate::InvalidField;
use serde::{Deserialize, Serialize};

/// A scalar history through knots `(t_k, y_k)` \[s, unit\], joined by smooth C¹ steps
/// (`y = y_k + (y_{k+1} − y_k)(3τ² − 2τ³)`), constant before the first and after the last knot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct Schedule {
    /// Knots, times strictly increasing.
    pub knots: Vec<(f64, f64)>,
}

impl Schedule {
    /// A constant value.
    pub fn constant(y: f64) -> Self {
        Self {
            knots: vec![(0.0, y)],
        }
    }

    /// Value and rate `(y, ẏ)` at `t`.
    pub fn eval(&self, t: f64) -> (f64, f64) {
        let k = &self.knots;
        match k.len() {
            0 => (0.0, 0.0),
            _ if t <= k[0].0 => (k[0].1, 0.0),
            _ if t >= k[k.len() - 1].0 => (k[k.len() - 1].1, 0.0),
            _ => {
                let j = k.partition_point(|p| p.0 <= t) - 1;
                let ((t0, y0), (t1, y1)) = (k[j], k[j + 1]);
                let tau = (t - t0) / (t1 - t0);
                let s = tau * tau * (3.0 - 2.0 * tau);
                let ds = 6.0 * tau * (1.0 - tau) / (t1 - t0);
                (y0 + (y1 - y0) * s, (y1 - y0) * ds)
            }
        }
    }

    /// Value at `t`.
    pub fn value(&self, t: f64) -> f64 {
        self.eval(t).0
    }

    /// Checks that the knot times are finite and strictly increasing; the error names the knot
    /// (`knots[i]`, relative to the schedule).
    pub fn validate(&self) -> Result<(), InvalidField> {
        for (i, w) in self.knots.windows(2).enumerate() {
            if w[1].0.partial_cmp(&w[0].0) != Some(std::cmp::Ordering::Greater) {
                return Err(InvalidField::new(
                    format!("knots[{}]", i + 1),
                    "times must increase strictly",
                ));
            }
        }
        if self
            .knots
            .iter()
            .any(|(t, y)| !t.is_finite() || !y.is_finite())
        {
            return Err(InvalidField::new("knots", "values must be finite"));
        }
        Ok(())
    }
}

/// One harmonic `A sin(Ω t + φ)` of a [`Signal`] (a crankshaft firing order, an accessory's
/// load ripple).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Harmonic {
    /// Amplitude `A` \[unit of the signal\].
    pub amplitude: f64,
    /// Circular frequency `Ω` \[rad/s\].
    pub frequency: f64,
    /// Phase `φ` \[rad\].
    #[serde(default)]
    pub phase: f64,
}

/// A prescribed history: a [`Schedule`] plus harmonics faded in over `ramp` seconds,
///
/// ```text
///   y(t) = y_schedule(t) + h(t/ramp) Σ A_k sin(Ω_k t + φ_k),   h(τ) = 3τ² − 2τ³ (τ ≤ 1), 1 after
/// ```
///
/// (the driver speed of an engine: mean speed plus the firing-order fluctuations; an
/// accessory's load torque with its ripple). `ramp = 0` applies the harmonics at once.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
#[serde(default, deny_unknown_fields)]
pub struct Signal {
    /// The smooth part.
    pub schedule: Schedule,
    /// Harmonics added to it.
    pub harmonics: Vec<Harmonic>,
    /// Fade-in time of the harmonics \[s\].
    pub ramp: f64,
}

impl From<Schedule> for Signal {
    fn from(schedule: Schedule) -> Self {
        Self {
            schedule,
            ..Default::default()
        }
    }
}

impl Signal {
    /// A constant value.
    pub fn constant(y: f64) -> Self {
        Schedule::constant(y).into()
    }

    /// Value and rate `(y, ẏ)` at `t`.
    pub fn eval(&self, t: f64) -> (f64, f64) {
        let (mut y, mut dy) = self.schedule.eval(t);
        if self.harmonics.is_empty() {
            return (y, dy);
        }
        let (h, dh) = if self.ramp > 0.0 && t < self.ramp {
            let tau = t.max(0.0) / self.ramp;
            (
                tau * tau * (3.0 - 2.0 * tau),
                6.0 * tau * (1.0 - tau) / self.ramp,
            )
        } else {
            (1.0, 0.0)
        };
        for k in &self.harmonics {
            let (s, c) = (k.frequency * t + k.phase).sin_cos();
            y += h * k.amplitude * s;
            dy += h * k.amplitude * k.frequency * c + dh * k.amplitude * s;
        }
        (y, dy)
    }

    /// Value at `t`.
    pub fn value(&self, t: f64) -> f64 {
        self.eval(t).0
    }

    /// Checks the schedule and that the harmonics and the ramp are finite (ramp ≥ 0).
    pub fn validate(&self) -> Result<(), InvalidField> {
        self.schedule.validate().map_err(|e| e.within("schedule"))?;
        for (i, k) in self.harmonics.iter().enumerate() {
            for (name, v) in [
                ("amplitude", k.amplitude),
                ("frequency", k.frequency),
                ("phase", k.phase),
            ] {
                mbd_core::validate::check::finite(&format!("harmonics[{i}].{name}"), v)?;
            }
        }
        mbd_core::validate::check::non_negative("ramp", self.ramp, "s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // The rate of a signal with harmonics and a ramp against central differences.
    #[test]
    fn signal_rate_matches_differences() {
        let s = Signal {
            schedule: Schedule {
                knots: vec![(0.0, 10.0), (0.3, 20.0)],
            },
            harmonics: vec![Harmonic {
                amplitude: 2.0,
                frequency: 40.0,
                phase: 0.3,
            }],
            ramp: 0.2,
        };
        for &t in &[0.05, 0.15, 0.25, 0.5] {
            let h = 1e-6;
            let fd = (s.value(t + h) - s.value(t - h)) / (2.0 * h);
            assert!((fd - s.eval(t).1).abs() < 1e-5 * fd.abs().max(1.0), "{t}");
        }
        // after the ramp: mean plus the full harmonic
        let t = 0.7;
        assert!((s.value(t) - 20.0 - 2.0 * (40.0 * t + 0.3).sin()).abs() < 1e-12);
    }

    #[test]
    fn smooth_steps_hit_knots_and_rates_match_differences() {
        let s = Schedule {
            knots: vec![(0.0, 0.0), (0.5, 60.0), (1.0, 60.0), (1.2, 10.0)],
        };
        assert_eq!(s.value(-1.0), 0.0);
        assert_eq!(s.value(0.5), 60.0);
        assert_eq!(s.value(0.75), 60.0);
        assert_eq!(s.value(5.0), 10.0);
        for &t in &[0.1, 0.37, 1.05, 1.19] {
            let h = 1e-6;
            let fd = (s.value(t + h) - s.value(t - h)) / (2.0 * h);
            assert!((fd - s.eval(t).1).abs() < 1e-5 * fd.abs().max(1.0));
        }
    }
}
