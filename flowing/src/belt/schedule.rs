//! Time histories of prescribed quantities (driver speed, load torque).

use mbd_core::validate::InvalidField;
use serde::{Deserialize, Serialize};

/// A scalar history through knots `(t_k, y_k)` \[s, unit\], joined by smooth C¹ steps
/// (`y = y_k + (y_{k+1} − y_k)(3τ² − 2τ³)`), constant before the first and after the last knot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
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

#[cfg(test)]
mod tests {
    use super::*;

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
