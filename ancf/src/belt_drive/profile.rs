//! Time histories of the pulley inputs: prescribed driver speeds (Kerkkänen (3.29)) and load
//! torques on free pulleys (Kerkkänen (3.30)).

use mbd_core::validate::{InvalidField, Validate};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// A prescribed pulley speed `ω(t)` \[rad/s\], positive when the belt travels along the path
/// direction (see [`super::Pulley`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum SpeedProfile {
    /// `ω(t) = omega` \[rad/s\].
    Constant {
        /// Speed \[rad/s\].
        omega: f64,
    },
    /// Kerkkänen (3.29) generalised: `0` for `t ≤ t_start`, linear ramp to `omega` at `t_end`,
    /// then `omega` (thesis: `t_start = 0.05 s`, `t_end = 0.6 s`, `omega = 12 rad/s`).
    Ramp {
        /// End of the rest phase \[s\].
        t_start: f64,
        /// End of the ramp \[s\].
        t_end: f64,
        /// Final speed \[rad/s\].
        omega: f64,
    },
}

impl SpeedProfile {
    /// Kerkkänen (3.29) with final speed `omega` \[rad/s\].
    pub fn kerkkanen(omega: f64) -> Self {
        SpeedProfile::Ramp {
            t_start: 0.05,
            t_end: 0.6,
            omega,
        }
    }

    /// `[ω(t), ω̇(t)]` \[rad/s, rad/s²\].
    pub fn eval(&self, t: f64) -> [f64; 2] {
        match *self {
            SpeedProfile::Constant { omega } => [omega, 0.0],
            SpeedProfile::Ramp {
                t_start,
                t_end,
                omega,
            } => {
                if t <= t_start {
                    [0.0, 0.0]
                } else if t <= t_end {
                    let r = omega / (t_end - t_start);
                    [r * (t - t_start), r]
                } else {
                    [omega, 0.0]
                }
            }
        }
    }

    /// Final (steady) speed \[rad/s\].
    pub fn final_speed(&self) -> f64 {
        match *self {
            SpeedProfile::Constant { omega } | SpeedProfile::Ramp { omega, .. } => omega,
        }
    }
}

impl Validate for SpeedProfile {
    /// Check the parameters; the error names the offending field (relative path).
    fn validate(&self) -> Result<(), InvalidField> {
        match *self {
            SpeedProfile::Constant { omega } if !omega.is_finite() => Err(InvalidField::new(
                "omega",
                format!("must be finite, got {omega}"),
            )),
            SpeedProfile::Ramp {
                t_start,
                t_end,
                omega,
            } => {
                if !omega.is_finite() {
                    Err(InvalidField::new(
                        "omega",
                        format!("must be finite, got {omega}"),
                    ))
                } else if !(t_start.is_finite() && t_end.is_finite() && t_end > t_start) {
                    Err(InvalidField::new(
                        "t_end",
                        format!("must exceed t_start ({t_start} s), got {t_end} s"),
                    ))
                } else {
                    Ok(())
                }
            }
            _ => Ok(()),
        }
    }
}

/// A load torque `T_a(t)` \[N·m\] on a free pulley; it opposes the pulley's rotation in the
/// travel direction (Kerkkänen (3.26): "opposing torque of the driven accessories").
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum TorqueProfile {
    /// No load.
    #[serde(deserialize_with = "mbd_core::validate::unit_variant")]
    None,
    /// `T_a(t) = torque` \[N·m\].
    Constant {
        /// Torque \[N·m\].
        torque: f64,
    },
    /// Kerkkänen (3.30) as printed: `0` for `t ≤ t_start`, `(T/2)(1 − cos(π t / t_end))` for
    /// `t_start < t ≤ t_end`, `T` afterwards (thesis: `t_start = 0.05 s`, `t_end = 0.6 s`,
    /// `T = 45 N·m`; the printed form jumps by 0.767 N·m at `t_start`, seed note §5).
    Cosine {
        /// Start \[s\].
        t_start: f64,
        /// End of the ramp \[s\].
        t_end: f64,
        /// Final torque \[N·m\].
        torque: f64,
    },
}

impl TorqueProfile {
    /// Kerkkänen (3.30) with final torque `torque` \[N·m\].
    pub fn kerkkanen(torque: f64) -> Self {
        TorqueProfile::Cosine {
            t_start: 0.05,
            t_end: 0.6,
            torque,
        }
    }

    /// `T_a(t)` \[N·m\].
    pub fn eval(&self, t: f64) -> f64 {
        match *self {
            TorqueProfile::None => 0.0,
            TorqueProfile::Constant { torque } => torque,
            TorqueProfile::Cosine {
                t_start,
                t_end,
                torque,
            } => {
                if t <= t_start {
                    0.0
                } else if t <= t_end {
                    0.5 * torque * (1.0 - (PI * t / t_end).cos())
                } else {
                    torque
                }
            }
        }
    }

    /// Final (steady) torque \[N·m\].
    pub fn final_torque(&self) -> f64 {
        match *self {
            TorqueProfile::None => 0.0,
            TorqueProfile::Constant { torque } | TorqueProfile::Cosine { torque, .. } => torque,
        }
    }
}

impl Validate for TorqueProfile {
    /// Check the parameters; the error names the offending field (relative path).
    fn validate(&self) -> Result<(), InvalidField> {
        match *self {
            TorqueProfile::None => Ok(()),
            TorqueProfile::Constant { torque } => {
                if torque.is_finite() {
                    Ok(())
                } else {
                    Err(InvalidField::new(
                        "torque",
                        format!("must be finite, got {torque}"),
                    ))
                }
            }
            TorqueProfile::Cosine {
                t_start,
                t_end,
                torque,
            } => {
                if !torque.is_finite() {
                    Err(InvalidField::new(
                        "torque",
                        format!("must be finite, got {torque}"),
                    ))
                } else if !(t_start.is_finite() && t_end.is_finite() && t_end > t_start) {
                    Err(InvalidField::new(
                        "t_end",
                        format!("must exceed t_start ({t_start} s), got {t_end} s"),
                    ))
                } else {
                    Ok(())
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference: Kerkkänen (3.29) and (3.30) evaluated by hand.
    #[test]
    fn kerkkanen_profiles() {
        let w = SpeedProfile::kerkkanen(12.0);
        assert_eq!(w.eval(0.04), [0.0, 0.0]);
        let [o, a] = w.eval(0.325);
        assert!((o - 6.0).abs() < 1e-12 && (a - 12.0 / 0.55).abs() < 1e-12);
        assert_eq!(w.eval(1.0), [12.0, 0.0]);
        let t = TorqueProfile::kerkkanen(45.0);
        assert_eq!(t.eval(0.05), 0.0);
        assert!((t.eval(0.3) - 22.5).abs() < 1e-12);
        assert!((t.eval(0.6) - 45.0).abs() < 1e-12);
        // the printed form jumps by 22.5 (1 − cos(π·0.05/0.6)) just after t_start
        assert!((t.eval(0.050_000_001) - 0.7670).abs() < 1e-3);
    }
}
