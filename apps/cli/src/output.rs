//! The output folder of a study.

use crate::error::CliError;
use serde::Serialize;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// A study's output folder (created on demand).
#[derive(Debug, Clone)]
pub struct OutputDir {
    root: PathBuf,
}

impl OutputDir {
    /// Create (if needed) the folder `root`.
    pub fn create(root: impl Into<PathBuf>) -> Result<Self, CliError> {
        let root = root.into();
        std::fs::create_dir_all(&root).map_err(|e| CliError::Write {
            path: root.clone(),
            message: e.to_string(),
        })?;
        Ok(Self { root })
    }

    /// The folder.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// Path of a file `name` inside the folder.
    pub fn path(&self, name: &str) -> PathBuf {
        self.root.join(name)
    }

    /// Write `value` as pretty JSON to `name`.
    pub fn write_json<T: Serialize>(&self, name: &str, value: &T) -> Result<PathBuf, CliError> {
        let path = self.path(name);
        let text = serde_json::to_string_pretty(value).map_err(|e| write_error(&path, e))?;
        std::fs::write(&path, text + "\n").map_err(|e| write_error(&path, e))?;
        Ok(path)
    }

    /// Write a whole numeric table as CSV with a header row.
    pub fn write_csv<R>(&self, name: &str, header: &[&str], rows: R) -> Result<PathBuf, CliError>
    where
        R: IntoIterator,
        R::Item: AsRef<[f64]>,
    {
        let mut sink = self.csv(name, header)?;
        for row in rows {
            sink.row(row.as_ref())?;
        }
        sink.finish()
    }

    /// Open a CSV file for streaming rows (histories are written as they are computed, so a
    /// failed run keeps what it had).
    pub fn csv(&self, name: &str, header: &[&str]) -> Result<CsvSink, CliError> {
        let path = self.path(name);
        let file = File::create(&path).map_err(|e| write_error(&path, e))?;
        let mut writer = csv::Writer::from_writer(BufWriter::new(file));
        writer
            .write_record(header)
            .map_err(|e| write_error(&path, e))?;
        Ok(CsvSink {
            path,
            writer,
            columns: header.len(),
        })
    }
}

/// Unit suffixes a CSV column name may end with (`torque_Nm`, `delta_omega_rad_s`, `t_s`):
/// `_s`, `_m`, `_n` (newton), `_n_m` (N/m), `_Nm` (N·m), `_hz`, `_kmh`, `_rad`, `_rad_s`,
/// `_rad_s2`, `_rad2_s2`, `_1_s`, `_m_s`, `_m_s2`, `_j`, `_kg`, `_kg_m2`, `_pa`, `_deg`,
/// `_n_sqrtkg` (N/√kg), `_sqrtkg_m` (√kg·m, mass-normalised modal coordinates), `_rpm`
/// (revolutions per minute) and `_percent`; the SI symbols spelled out are accepted too
/// (`tension_N`, `torque_N_m`, `pressure_N_per_m`, `slip_velocity_m_per_s`). Suffixes
/// compare without case ([`column_has_unit`]).
pub const UNIT_SUFFIXES: &[&str] = &[
    "_s",
    "_m",
    "_n",
    "_n_m",
    "_Nm",
    "_hz",
    "_kmh",
    "_rad",
    "_rad_s",
    "_rad_s2",
    "_rad2_s2",
    "_1_s",
    "_m_s",
    "_m_s2",
    "_j",
    "_kg",
    "_kg_m2",
    "_pa",
    "_deg",
    "_n_sqrtkg",
    "_sqrtkg_m",
    "_rpm",
    "_percent",
    "_N",
    "_N_m",
    "_N_per_m",
    "_m_per_s",
];

/// Suffixes of dimensionless columns (`damping_ratio`, `lateral_share`, `loaded_flag`,
/// `pulley_index`, `direction_code`, `active_count`, `friction_utilisation` = |f_t| / (μ f_n))
/// and names that are dimensionless by definition (`mode`, `n`, `strain`).
pub const DIMENSIONLESS: &[&str] = &[
    "_ratio",
    "_share",
    "_flag",
    "_index",
    "_code",
    "_count",
    "_strain",
    "_utilisation",
];

/// Column names that are counts or indices by definition (`pulley`: the pulley's index in
/// travel order).
pub const DIMENSIONLESS_NAMES: &[&str] = &["mode", "n", "strain", "index", "pulley"];

/// Whether the CSV column `name` says its unit (ends with one of [`UNIT_SUFFIXES`]) or that
/// it is dimensionless ([`DIMENSIONLESS`], [`DIMENSIONLESS_NAMES`]).
/// The suffixes compare without case: `tension_N` and `tension_n` both say newtons.
pub fn column_has_unit(name: &str) -> bool {
    let lower = name.to_ascii_lowercase();
    DIMENSIONLESS_NAMES.contains(&lower.as_str())
        || UNIT_SUFFIXES
            .iter()
            .chain(DIMENSIONLESS)
            .any(|u| lower.ends_with(&u.to_ascii_lowercase()) && lower.len() > u.len())
}

/// The columns without a unit in the headers of the CSV files in `dir` (recursively), as
/// `file: column` (empty when every column says its unit; issue 20's convention).
pub fn columns_without_unit(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return out;
    };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            out.extend(columns_without_unit(&p));
        } else if p.extension().is_some_and(|e| e == "csv")
            && let Ok(text) = std::fs::read_to_string(&p)
            && let Some(header) = text.lines().next()
        {
            for col in header.split(',') {
                if !column_has_unit(col) {
                    out.push(format!("{}: {col}", p.display()));
                }
            }
        }
    }
    out
}

/// A CSV file being written row by row.
pub struct CsvSink {
    path: PathBuf,
    writer: csv::Writer<BufWriter<File>>,
    columns: usize,
}

impl CsvSink {
    /// Append one row (must have as many values as the header has columns).
    pub fn row(&mut self, values: &[f64]) -> Result<(), CliError> {
        if values.len() != self.columns {
            return Err(CliError::Write {
                path: self.path.clone(),
                message: format!(
                    "row has {} values, header has {}",
                    values.len(),
                    self.columns
                ),
            });
        }
        self.writer
            .write_record(values.iter().map(|v| format!("{v:.10e}")))
            .map_err(|e| write_error(&self.path, e))
    }

    /// Flush to disk (also done on drop, silently).
    pub fn flush(&mut self) -> Result<(), CliError> {
        self.writer.flush().map_err(|e| write_error(&self.path, e))
    }

    /// Flush and return the file's path.
    pub fn finish(mut self) -> Result<PathBuf, CliError> {
        self.flush()?;
        Ok(self.path.clone())
    }
}

fn write_error(path: &Path, e: impl std::fmt::Display) -> CliError {
    CliError::Write {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // definition of the convention: a unit suffix or a dimensionless marker
    #[test]
    fn columns_say_their_units() {
        for ok in [
            "t_s",
            "torque_Nm",
            "delta_omega_rad_s",
            "fy_amp_n",
            "speed_kmh",
            "damping_ratio",
            "mode",
            "pulley_index",
            "normal_force_n_m",
            "growth_rate_1_s",
            "tension_N",
            "pressure_N_per_m",
            "slip_velocity_m_per_s",
            "friction_utilisation",
            "pulley",
        ] {
            assert!(column_has_unit(ok), "{ok}");
        }
        for bad in ["t", "torque", "hz", "delta_omega", "tension", "_s", "x"] {
            assert!(!column_has_unit(bad), "{bad}");
        }
    }

    #[test]
    fn csv_round_trip_and_row_length_check() {
        let dir = std::env::temp_dir().join(format!("flowmbd-cli-out-{}", std::process::id()));
        let out = OutputDir::create(&dir).unwrap();
        let p = out
            .write_csv("t.csv", &["t", "x"], [[0.0, 1.5], [0.5, -2.0]])
            .unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("t,x"));
        let second: Vec<f64> = lines
            .nth(1)
            .unwrap()
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(second, vec![0.5, -2.0]);
        let mut sink = out.csv("u.csv", &["a", "b"]).unwrap();
        assert!(sink.row(&[1.0]).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
