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
