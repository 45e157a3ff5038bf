//! A measured crankshaft speed trace read from a CSV file (issue 36 item 5): the FEAD study's
//! `[engine] trace = { file = "crank.csv", abscissa = "time" | "angle" }`.
//!
//! The file has two columns, the abscissa and the crank speed `ω` \[rad/s\]:
//!
//! * `abscissa = "time"`: time `t` \[s\];
//! * `abscissa = "angle"`: crank angle `θ` \[rad\] (a record sampled per degree of crank
//!   angle), converted to time by integrating `dt = dθ/ω` with `ω` linear in `θ` between
//!   samples, exactly:
//!
//! ```text
//!   Δt_k = Δθ_k · (ln ω_{k+1} − ln ω_k) / (ω_{k+1} − ω_k)     (Δθ_k/ω_k when ω_{k+1} = ω_k)
//! ```
//!
//! The time origin is the first sample's (the trace's own times are shifted to start at 0);
//! between samples the speed is linear in time ([`belt::Shape::Trace`]).
//!
//! Format: comma-separated, one sample per line; blank lines and lines starting with `#` are
//! skipped; the first other line may be a header (it is skipped if its first field is not a
//! number). The abscissa must increase strictly, every value be finite, and an angle trace's
//! speeds be positive. The reader is bounded: only a regular file of at most
//! [`MAX_TRACE_BYTES`] is read, at most [`belt::signal::MAX_KNOTS`] samples; every error names
//! the file, and the line where the content is at fault ([`TraceError`]).

use mbd_core::validate::InvalidField;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Largest trace file read \[bytes\] (16 MiB).
pub const MAX_TRACE_BYTES: u64 = 16 * 1024 * 1024;

/// What the first column of a trace is.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum Abscissa {
    /// Time \[s\].
    #[default]
    Time,
    /// Crank angle \[rad\].
    Angle,
}

/// A crankshaft speed trace in a CSV file (module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CrankTrace {
    /// The CSV file (a relative path is resolved against the configuration file's folder by
    /// the app: [`CrankTrace::resolved_against`]).
    pub file: PathBuf,
    /// The first column: `time` \[s\] (default) or `angle` \[rad\].
    #[serde(default)]
    pub abscissa: Abscissa,
    /// Repeat the trace for as long as the study runs (a record of whole engine cycles; the
    /// observation windows are then whole trace periods). `false`: play it once and hold its
    /// last speed.
    #[serde(default = "yes")]
    pub periodic: bool,
}

fn yes() -> bool {
    true
}

/// Why a trace could not be read (every variant names the file).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum TraceError {
    /// The file could not be opened or read.
    #[error("{file}: cannot read: {reason}")]
    Io {
        /// The file.
        file: String,
        /// The operating system's reason.
        reason: String,
    },
    /// Not a regular file (a directory, a device, a pipe).
    #[error("{file}: not a regular file")]
    NotRegular {
        /// The file.
        file: String,
    },
    /// Larger than [`MAX_TRACE_BYTES`].
    #[error("{file}: {size} bytes, more than the {max} allowed")]
    TooLarge {
        /// The file.
        file: String,
        /// Its size \[bytes\].
        size: u64,
        /// [`MAX_TRACE_BYTES`].
        max: u64,
    },
    /// A line that is not a valid sample.
    #[error("{file}:{line}: {reason}")]
    Line {
        /// The file.
        file: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// The trace as a whole is unusable (too few samples, too many).
    #[error("{file}: {reason}")]
    Content {
        /// The file.
        file: String,
        /// What is wrong.
        reason: String,
    },
}

impl TraceError {
    /// The error as an input error of the field `field` (`engine.trace.file`).
    pub fn within(&self, field: &str) -> InvalidField {
        InvalidField::new(field, self.to_string())
    }
}

impl CrankTrace {
    /// The same trace with a relative `file` taken relative to `dir` (the configuration
    /// file's folder).
    pub fn resolved_against(&self, dir: &Path) -> Self {
        let mut t = self.clone();
        if t.file.is_relative() {
            t.file = dir.join(&t.file);
        }
        t
    }

    /// Read the file: knots `(t_k, ω_k)` \[s, rad/s\] from `t = 0` (module documentation).
    ///
    /// # Errors
    /// [`TraceError`]: unreadable, not a regular file, too large, a malformed line (with its
    /// number), fewer than two samples.
    pub fn load(&self) -> Result<Vec<(f64, f64)>, TraceError> {
        use mbd_core::input::InputError as E;
        let name = self.file.display().to_string();
        let text =
            mbd_core::input::read_text(&self.file, MAX_TRACE_BYTES).map_err(|e| match e {
                E::Directory { .. } | E::NotRegular { .. } => {
                    TraceError::NotRegular { file: name.clone() }
                }
                E::TooLarge { size, max, .. } => TraceError::TooLarge {
                    file: name.clone(),
                    size,
                    max,
                },
                E::NotFound { source, .. } | E::Io { source, .. } => TraceError::Io {
                    file: name.clone(),
                    reason: source.to_string(),
                },
                E::NotUtf8 { .. } => TraceError::Io {
                    file: name.clone(),
                    reason: e.reason(),
                },
            })?;
        parse(&text, &name, self.abscissa)
    }
}

/// The knots of a trace's text (`name` for the messages; module documentation).
///
/// # Errors
/// [`TraceError::Line`] for a malformed line, [`TraceError::Content`] for fewer than two or
/// more than [`belt::signal::MAX_KNOTS`] samples.
pub fn parse(text: &str, name: &str, abscissa: Abscissa) -> Result<Vec<(f64, f64)>, TraceError> {
    let at = |line: usize, reason: String| TraceError::Line {
        file: name.to_string(),
        line,
        reason,
    };
    let mut raw: Vec<(f64, f64)> = Vec::new();
    let mut header_allowed = true;
    for (i, l) in text.lines().enumerate() {
        let line = i + 1;
        let l = l.trim();
        if l.is_empty() || l.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = l.split(',').map(str::trim).collect();
        let first_is_number = fields[0].parse::<f64>().is_ok();
        if header_allowed && !first_is_number {
            header_allowed = false;
            continue;
        }
        header_allowed = false;
        if fields.len() != 2 {
            return Err(at(
                line,
                format!(
                    "expected 2 columns (abscissa, speed), found {}",
                    fields.len()
                ),
            ));
        }
        let num = |k: usize, what: &str| -> Result<f64, TraceError> {
            match fields[k].parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(at(
                    line,
                    format!("{what} '{}' is not a finite number", fields[k]),
                )),
            }
        };
        let x = num(0, "abscissa")?;
        let w = num(1, "speed")?;
        if let Some(&(xp, _)) = raw.last()
            && x <= xp
        {
            return Err(at(
                line,
                format!("the abscissa must increase strictly ({x} after {xp})"),
            ));
        }
        if abscissa == Abscissa::Angle && w <= 0.0 {
            return Err(at(
                line,
                format!("speed {w} rad/s: an angle trace needs positive speeds (dt = dθ/ω)"),
            ));
        }
        if raw.len() >= belt::signal::MAX_KNOTS {
            return Err(TraceError::Content {
                file: name.to_string(),
                reason: format!("more than {} samples", belt::signal::MAX_KNOTS),
            });
        }
        raw.push((x, w));
    }
    if raw.len() < 2 {
        return Err(TraceError::Content {
            file: name.to_string(),
            reason: format!("needs at least 2 samples, found {}", raw.len()),
        });
    }
    Ok(match abscissa {
        Abscissa::Time => raw.iter().map(|&(t, w)| (t - raw[0].0, w)).collect(),
        Abscissa::Angle => angle_to_time(&raw),
    })
}

/// `(θ_k, ω_k)` → `(t_k, ω_k)` with `t_0 = 0` and the exact `Δt` of `ω` linear in `θ`
/// (module documentation).
pub fn angle_to_time(samples: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut t = 0.0;
    let mut out = Vec::with_capacity(samples.len());
    out.push((0.0, samples[0].1));
    for p in samples.windows(2) {
        let ((a0, w0), (a1, w1)) = (p[0], p[1]);
        let dw = w1 - w0;
        // (ln w1 − ln w0)/(w1 − w0), by its series near w1 = w0
        let r = dw / w0;
        let inv = if r.abs() < 1e-6 {
            (1.0 - 0.5 * r + r * r / 3.0) / w0
        } else {
            (w1 / w0).ln() / dw
        };
        t += (a1 - a0) * inv;
        out.push((t, w1));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    // dt = dθ/ω: a constant speed gives t = θ/ω; a linear ω(θ) = ω0 + g θ gives
    // t = ln(ω/ω0)/g (closed form).
    #[test]
    fn angle_to_time_is_exact_for_linear_speed_in_angle() {
        let k = angle_to_time(&[(0.0, 100.0), (2.0, 100.0)]);
        assert!((k[1].0 - 0.02).abs() < 1e-15);
        let (w0, g) = (80.0, 5.0);
        let s: Vec<(f64, f64)> = (0..=10).map(|i| (i as f64, w0 + g * i as f64)).collect();
        for (i, &(t, w)) in angle_to_time(&s).iter().enumerate() {
            let exact = (w / w0).ln() / g;
            assert!((t - exact).abs() < 1e-14, "sample {i}: {t} vs {exact}");
        }
    }

    // Malformed input: each error names the file and the line at fault.
    #[test]
    fn malformed_lines_are_named() {
        let cases = [
            ("t,w\n0,1\n0.1,x\n", 3, "not a finite number"),
            ("0,1\n0.1,2,3\n", 2, "expected 2 columns"),
            ("# c\n0,1\n0.1,2\n0.1,3\n", 4, "increase strictly"),
            ("0,1\n0.1,inf\n", 2, "finite"),
            ("t,w\nangle,w\n", 2, "not a finite number"),
        ];
        for (text, line, what) in cases {
            let e = parse(text, "crank.csv", Abscissa::Time).unwrap_err();
            let msg = e.to_string();
            assert!(
                msg.starts_with(&format!("crank.csv:{line}: ")) && msg.contains(what),
                "{text:?}: {msg}"
            );
        }
        let e = parse("0,100\n1,0\n", "a.csv", Abscissa::Angle).unwrap_err();
        assert!(e.to_string().starts_with("a.csv:2: "), "{e}");
        let e = parse("t,w\n0,1\n", "b.csv", Abscissa::Time).unwrap_err();
        assert!(matches!(e, TraceError::Content { .. }), "{e}");
    }
}
