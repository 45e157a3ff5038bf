//! The output folder of a study.
//!
//! Files are written through a temporary name in the same folder and renamed when complete
//! ([`write_atomic`]), so a file under its final name is never half written (a killed run
//! leaves at most a hidden `.NAME.part`). Every name a study writes is recorded (the
//! manifest, [`OutputDir::files`]); the runner lists it in `summary.json` (`"outputs"`), and a
//! new run in the same folder first removes the files the previous run listed
//! ([`OutputDir::begin_run`]), so stale outputs of an earlier run never stand beside new ones
//! unmarked (issue 35, item 3).

use crate::error::CliError;
use serde::Serialize;
use std::collections::BTreeSet;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// A study's output folder (created on demand) and the names written into it.
#[derive(Debug, Clone)]
pub struct OutputDir {
    root: PathBuf,
    written: Arc<Mutex<BTreeSet<String>>>,
}

/// The temporary name of `path` while it is written: `.NAME.part` beside it; with `keep_ext`
/// the extension stays last (`.NAME.part.png`: the plot backends pick the format from it).
pub fn part_path(path: &Path, keep_ext: bool) -> PathBuf {
    match (keep_ext, path.extension()) {
        (true, Some(ext)) => {
            let stem = path
                .file_stem()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            path.with_file_name(format!(".{stem}.part.{}", ext.to_string_lossy()))
        }
        _ => mbd_core::output::part_path(path),
    }
}

/// Write `bytes` to `path` through a temporary file in the same folder, renamed over `path`
/// when complete (atomic on one file system: readers see the old file or the whole new one;
/// [`mbd_core::output::write_atomic`]).
pub use mbd_core::output::write_atomic;

/// Whether `name` is a relative path of plain names inside the output folder (`vtk/a.vtk`; no
/// `..`, root or prefix), written with `/`.
fn inside(name: &str) -> bool {
    !name.is_empty()
        && !name.contains('\\')
        && name
            .split('/')
            .all(|c| !c.is_empty() && c != "." && c != "..")
        && Path::new(name)
            .components()
            .all(|c| matches!(c, std::path::Component::Normal(_)))
}

impl OutputDir {
    /// Create (if needed) the folder `root`. A path that exists and is not a folder, or a
    /// folder that cannot be created or written, is bad input (exit code 2) naming `--out`.
    pub fn create(root: impl Into<PathBuf>) -> Result<Self, CliError> {
        let root = root.into();
        let bad = |message: String| CliError::OutDir {
            path: root.clone(),
            message,
        };
        if let Ok(m) = std::fs::metadata(&root)
            && !m.is_dir()
        {
            return Err(bad("exists and is not a folder".into()));
        }
        std::fs::create_dir_all(&root).map_err(|e| bad(format!("cannot create folder: {e}")))?;
        // a folder we cannot write into is found now, not after the run
        let probe = root.join(".flowmbd-write-test.part");
        File::create(&probe)
            .and_then(|mut f| f.write_all(b"x").and_then(|_| f.sync_all()))
            .map_err(|e| bad(format!("cannot write into the folder: {e}")))?;
        let _ = std::fs::remove_file(&probe);
        Ok(Self {
            root,
            written: Arc::default(),
        })
    }

    /// The folder.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// Path of a file `name` inside the folder, recorded in the manifest (for writers outside
    /// this type: plots, VTK; `name` may be a stem whose extensions the writer adds).
    pub fn path(&self, name: &str) -> PathBuf {
        if let Ok(mut w) = self.written.lock() {
            w.insert(name.to_string());
        }
        self.root.join(name)
    }

    /// The files of this run that exist in the folder: every recorded name, and every
    /// `name.ext` of a recorded stem (sorted).
    pub fn files(&self) -> Vec<String> {
        let names: BTreeSet<String> = self.written.lock().map(|w| w.clone()).unwrap_or_default();
        let mut out = BTreeSet::new();
        if let Ok(entries) = std::fs::read_dir(&self.root) {
            for e in entries.flatten() {
                let f = e.file_name().to_string_lossy().into_owned();
                if names.contains(&f)
                    || names.iter().any(|n| {
                        f.strip_prefix(n.as_str())
                            .and_then(|r| r.strip_prefix('.'))
                            .is_some_and(|ext| !ext.is_empty() && !ext.contains('.'))
                    })
                {
                    out.insert(f);
                }
            }
        }
        // files of this run inside sub-folders (`vtk/rest_0000.vtk`): listed one by one, so
        // that the next run removes exactly these (issue 35: frames of an earlier, longer run
        // stayed in `vtk/` unmarked)
        for n in names.iter().filter(|n| n.contains('/')) {
            if inside(n) && self.root.join(n).is_file() {
                out.insert(n.clone());
            }
        }
        // and the files in a recorded sub-folder (`vtk`, written by VTK series writers)
        for n in names.iter().filter(|n| inside(n)) {
            let Ok(entries) = std::fs::read_dir(self.root.join(n)) else {
                continue;
            };
            for e in entries.flatten() {
                let f = e.file_name().to_string_lossy().into_owned();
                if e.file_type().is_ok_and(|t| t.is_file()) && inside(&f) {
                    out.insert(format!("{n}/{f}"));
                }
            }
        }
        out.into_iter().collect()
    }

    /// Start a run in this folder: remove the files the previous run listed in its
    /// `summary.json` (`"outputs"`; plain names inside the folder only), then mark the folder
    /// as holding an unfinished run (`summary.json` with `"complete": false`).
    pub fn begin_run(&self) -> Result<(), CliError> {
        let summary = self.root.join("summary.json");
        if let Ok(text) = std::fs::read_to_string(&summary)
            && let Ok(v) = serde_json::from_str::<serde_json::Value>(&text)
            && let Some(files) = v.get("outputs").and_then(|f| f.as_array())
        {
            for f in files.iter().filter_map(|f| f.as_str()) {
                let plain = !f.is_empty()
                    && !f.contains(['/', '\\'])
                    && f != "."
                    && f != ".."
                    && Path::new(f).file_name().is_some_and(|n| n == f);
                if plain && f != "summary.json" {
                    let _ = std::fs::remove_file(self.root.join(f));
                } else if inside(f) {
                    // a file in a sub-folder of the run; the folder goes once empty
                    let path = self.root.join(f);
                    if path.is_file() {
                        let _ = std::fs::remove_file(&path);
                    }
                    let mut dir = path.parent();
                    while let Some(d) = dir
                        && d != self.root
                        && std::fs::remove_dir(d).is_ok()
                    {
                        dir = d.parent();
                    }
                }
            }
        }
        self.write_json(
            "summary.json",
            &serde_json::json!({ "complete": false, "status": "running" }),
        )?;
        Ok(())
    }

    /// Write `value` as pretty JSON to `name` (atomically).
    pub fn write_json<T: Serialize>(&self, name: &str, value: &T) -> Result<PathBuf, CliError> {
        let text = serde_json::to_string_pretty(value).map_err(|e| write_error(&self.root, e))?;
        self.write_text(name, &(text + "\n"))
    }

    /// Write `text` to `name` (atomically).
    pub fn write_text(&self, name: &str, text: &str) -> Result<PathBuf, CliError> {
        let path = self.path(name);
        write_atomic(&path, text.as_bytes()).map_err(|e| write_error(&path, e))?;
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
    /// failed run keeps what it had): rows go to `.NAME.part`, renamed to `NAME` by
    /// [`CsvSink::finish`] or when the sink is dropped (a failed or interrupted run keeps its
    /// rows under the final name; `summary.json` says the run is incomplete).
    pub fn csv(&self, name: &str, header: &[&str]) -> Result<CsvSink, CliError> {
        let path = self.path(name);
        let part = part_path(&path, false);
        let file = File::create(&part).map_err(|e| write_error(&path, e))?;
        let mut writer = csv::Writer::from_writer(BufWriter::new(file));
        writer
            .write_record(header)
            .map_err(|e| write_error(&path, e))?;
        Ok(CsvSink {
            path,
            part,
            writer: Some(writer),
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

/// A CSV file being written row by row (under a temporary name until finished or dropped).
pub struct CsvSink {
    path: PathBuf,
    part: PathBuf,
    writer: Option<csv::Writer<BufWriter<File>>>,
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
        let Some(w) = self.writer.as_mut() else {
            return Err(write_error(&self.path, "already finished"));
        };
        w.write_record(values.iter().map(|v| format!("{v:.10e}")))
            .map_err(|e| write_error(&self.path, e))
    }

    /// Flush to disk (also done on drop, silently).
    pub fn flush(&mut self) -> Result<(), CliError> {
        match self.writer.as_mut() {
            Some(w) => w.flush().map_err(|e| write_error(&self.path, e)),
            None => Ok(()),
        }
    }

    /// Flush, move the file to its final name and return that path.
    pub fn finish(mut self) -> Result<PathBuf, CliError> {
        self.close()?;
        Ok(self.path.clone())
    }

    fn close(&mut self) -> Result<(), CliError> {
        if let Some(mut w) = self.writer.take() {
            w.flush().map_err(|e| write_error(&self.path, e))?;
            drop(w);
            std::fs::rename(&self.part, &self.path).map_err(|e| write_error(&self.path, e))?;
        }
        Ok(())
    }
}

impl Drop for CsvSink {
    fn drop(&mut self) {
        let _ = self.close();
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

    // issue 35 item 3: the files a run wrote into a sub-folder (VTK frames) are listed one by
    // one and removed by the next run, the folder too once empty; a user's file beside them
    // and names reaching outside the folder are left alone
    #[test]
    fn files_in_sub_folders_are_listed_and_cleared() {
        let dir = std::env::temp_dir().join(format!("flowmbd-cli-sub-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let out = OutputDir::create(&dir).unwrap();
        let vtk = out.path("vtk");
        std::fs::create_dir_all(&vtk).unwrap();
        for k in 0..3 {
            std::fs::write(vtk.join(format!("f_{k}.vtk")), "x").unwrap();
        }
        out.write_text("a.csv", "t_s\n").unwrap();
        let files = out.files();
        assert_eq!(
            files,
            vec!["a.csv", "vtk", "vtk/f_0.vtk", "vtk/f_1.vtk", "vtk/f_2.vtk"],
            "{files:?}"
        );
        out.write_json("summary.json", &serde_json::json!({ "outputs": files }))
            .unwrap();
        // the next run starts: the listed files go, the emptied folder with them
        let next = OutputDir::create(&dir).unwrap();
        next.begin_run().unwrap();
        assert!(!dir.join("a.csv").exists());
        assert!(!vtk.exists(), "emptied vtk/ removed");
        // a folder holding a file the run did not list stays, with that file
        std::fs::create_dir_all(&vtk).unwrap();
        std::fs::write(vtk.join("f_0.vtk"), "x").unwrap();
        std::fs::write(vtk.join("mine.txt"), "x").unwrap();
        next.write_json(
            "summary.json",
            &serde_json::json!({ "outputs": ["vtk/f_0.vtk", "../escape.txt", "vtk/../../x"] }),
        )
        .unwrap();
        OutputDir::create(&dir).unwrap().begin_run().unwrap();
        assert!(!vtk.join("f_0.vtk").exists());
        assert!(vtk.join("mine.txt").exists());
        assert!(!inside("../escape.txt") && !inside("vtk/../../x") && !inside("/etc/x"));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
