//! The output folder of a study.
//!
//! Files are written through a temporary name in the same folder and renamed when complete
//! ([`write_atomic`]), so a file under its final name is never half written (a killed run
//! leaves at most a hidden `.NAME.part`). Every name a study writes is recorded (the
//! manifest, [`OutputDir::files`]); the runner lists it in `summary.json` (`"outputs"`), and a
//! new run in the same folder first removes the files the previous run listed
//! ([`OutputDir::begin_run`]), so stale outputs of an earlier run never stand beside new ones
//! unmarked (issue 35, item 3).
//!
//! CSV files follow one naming convention (issue 39, item 3), defined in the docs of
//! [`UNIT_SUFFIXES`]: every column name ends in its unit written from SI symbols in their SI case
//! (`t_s`, `torque_N_m`, `omega_rad_per_s`, `tension_N`, `frequency_Hz`, `speed_km_per_h`), in a
//! dimensionless marker (`damping_ratio`) or in an integer marker (`pulley_index`,
//! `gross_slip_flag`); [`CsvSink::row`] writes the integer columns as integers and
//! [`csv_violations`] checks a folder of CSV files against the convention.

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
        let text =
            serde_json::to_string_pretty(value).map_err(|e| CliError::write(&self.root, e))?;
        self.write_text(name, &(text + "\n"))
    }

    /// Write `text` to `name` (atomically).
    pub fn write_text(&self, name: &str, text: &str) -> Result<PathBuf, CliError> {
        let path = self.path(name);
        write_atomic(&path, text.as_bytes()).map_err(|e| CliError::write(&path, e))?;
        Ok(path)
    }

    /// Write a whole numeric table as CSV with a header row (column names as `&str` or
    /// `String`).
    pub fn write_csv<R, S>(&self, name: &str, header: &[S], rows: R) -> Result<PathBuf, CliError>
    where
        S: AsRef<str>,
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
    /// rows under the final name; `summary.json` says the run is incomplete). Column names
    /// as `&str` or `String`.
    pub fn csv<S: AsRef<str>>(&self, name: &str, header: &[S]) -> Result<CsvSink, CliError> {
        let path = self.path(name);
        let part = part_path(&path, false);
        let file = File::create(&part).map_err(|e| CliError::write(&path, e))?;
        let mut writer = csv::Writer::from_writer(BufWriter::new(file));
        let names: Vec<String> = header.iter().map(|c| c.as_ref().to_string()).collect();
        writer
            .write_record(&names)
            .map_err(|e| CliError::write(&path, e))?;
        Ok(CsvSink {
            path,
            part,
            writer: Some(writer),
            kinds: names
                .iter()
                .map(|c| column_kind(c).unwrap_or(ColumnKind::Real))
                .collect(),
            names,
        })
    }
}

/// The unit suffixes of CSV column names (the one convention of every CSV a study writes,
/// issue 39 item 3). A column is named `quantity_UNIT`, where `UNIT` is written from SI
/// symbols in their SI case (`s`, `m`, `kg`, `N`, `J`, `W`, `Pa`, `Hz`, `rad`; case matters:
/// `N` is the newton, `n` a count), a product joined by `_` (`N_m` = N·m, `kg_m2` = kg·m²), a
/// quotient by `_per_` (`rad_per_s`, `m_per_s2`, `N_per_m`, `1_per_s`), a power as a trailing
/// digit (`m2`, `s2`) and a square root as `sqrt_` (`N_per_sqrt_kg` = N/√kg, the spindle force
/// of a mass-normalised mode; `sqrt_kg_m` = √kg·m, a mass-normalised modal coordinate). Three
/// non-SI units are allowed where the field speaks them: `deg`, `rpm` (revolutions per minute)
/// and `km_per_h`; `percent` marks a percentage. Examples: `t_s`, `omega_driver_rad_per_s`,
/// `torque_N_m`, `tension_N`, `pressure_N_per_m`, `frequency_Hz`, `energy_J`, `speed_km_per_h`.
///
/// A dimensionless real column ends in [`DIMENSIONLESS`] (`damping_ratio`, `energy_share`,
/// `green_strain`); an integer column (an index, a count, a flag 0/1, a code) ends in
/// [`INTEGER_MARKERS`] or is one of [`INTEGER_NAMES`] and is written as an integer
/// ([`CsvSink::row`]). [`column_kind`] decides a name; [`csv_violations`] checks a folder.
pub const UNIT_SUFFIXES: &[&str] = &[
    "s",
    "m",
    "kg",
    "N",
    "J",
    "W",
    "Pa",
    "Hz",
    "rad",
    "deg",
    "rpm",
    "percent",
    "km_per_h",
    "m2",
    "N_m",
    "N_per_m",
    "rad_per_s",
    "rad_per_s2",
    "rad2_per_s2",
    "1_per_s",
    "m_per_s",
    "m_per_s2",
    "kg_m2",
    "N_per_sqrt_kg",
    "sqrt_kg_m",
];

/// Spellings of units that the convention replaced ([`UNIT_SUFFIXES`] gives the one form):
/// `_rad_s` → `_rad_per_s`, `_m_s` → `_m_per_s`, `_1_s` → `_1_per_s`, `_Nm` and `_n_m` (which
/// meant N/m in some files) → `_N_m` / `_N_per_m`, `_kmh` → `_km_per_h`, lower-case `_n`,
/// `_j`, `_pa`, `_hz`, `_w` → `_N`, `_J`, `_Pa`, `_Hz`, `_W`. A name ending in one of these is
/// outside the convention even where its last part alone would read as a unit (`rad_s` ends in
/// `_s`).
pub const LEGACY_SUFFIXES: &[&str] = &[
    "rad_s", "rad_s2", "rad2_s2", "m_s", "m_s2", "1_s", "Nm", "n_m", "kmh", "n_sqrtkg", "sqrtkg_m",
    "n", "j", "pa", "hz", "w",
];

/// Suffixes of dimensionless real columns (`damping_ratio`, `lateral_share`, `green_strain`).
pub const DIMENSIONLESS: &[&str] = &["ratio", "share", "strain"];

/// Suffixes of integer columns: an index (`pulley_index`), a count (`active_nodes_count`), a
/// flag 0/1 (`gross_slip_flag`), a code (`direction_code`: its meaning in the study's docs).
pub const INTEGER_MARKERS: &[&str] = &["index", "count", "flag", "code"];

/// Column names that are integers by definition: `mode` (the mode number) and `n` (a wave or
/// harmonic number).
pub const INTEGER_NAMES: &[&str] = &["mode", "n"];

/// What a CSV column holds, read from its name ([`column_kind`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColumnKind {
    /// A real number with a unit or dimensionless (`{:.10e}`).
    Real,
    /// An integer (index, count, flag, code), written without a decimal point.
    Integer,
}

/// Whether `name` ends in `_suffix` after a non-empty stem.
fn ends_in(name: &str, suffix: &str) -> bool {
    name.len() > suffix.len() + 1
        && name.ends_with(suffix)
        && name.as_bytes()[name.len() - suffix.len() - 1] == b'_'
}

/// The kind of the CSV column `name` under the one convention ([`UNIT_SUFFIXES`]), or `None`
/// when the name is outside it (no unit, a unit spelled another way, no integer marker).
/// Suffixes compare with their case: `tension_N` is in newtons, `tension_n` is refused.
pub fn column_kind(name: &str) -> Option<ColumnKind> {
    if INTEGER_NAMES.contains(&name) || INTEGER_MARKERS.iter().any(|u| ends_in(name, u)) {
        return Some(ColumnKind::Integer);
    }
    if LEGACY_SUFFIXES.iter().any(|u| ends_in(name, u)) {
        return None;
    }
    UNIT_SUFFIXES
        .iter()
        .chain(DIMENSIONLESS)
        .any(|u| ends_in(name, u))
        .then_some(ColumnKind::Real)
}

/// Whether the CSV column `name` follows the convention ([`column_kind`] is `Some`).
pub fn column_has_unit(name: &str) -> bool {
    column_kind(name).is_some()
}

/// Whether `cell` is an integer as [`CsvSink::row`] writes it (`3`, `-1`, `0`; `NaN` for a
/// missing value).
pub fn is_integer_cell(cell: &str) -> bool {
    cell == "NaN" || {
        let digits = cell.strip_prefix('-').unwrap_or(cell);
        !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit())
    }
}

/// The breaches of the CSV convention in the CSV files in `dir` (recursively), as
/// `file: column` for a header outside it ([`column_kind`]) and `file:line: column = cell`
/// for an integer column holding a cell that is not an integer ([`is_integer_cell`]). Empty
/// when every file follows the convention.
pub fn csv_violations(dir: &Path) -> Vec<String> {
    let mut out = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return out;
    };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            out.extend(csv_violations(&p));
        } else if p.extension().is_some_and(|e| e == "csv")
            && let Ok(text) = std::fs::read_to_string(&p)
        {
            let mut lines = text.lines();
            let Some(header) = lines.next() else {
                continue;
            };
            let cols: Vec<&str> = header.split(',').collect();
            let kinds: Vec<Option<ColumnKind>> = cols.iter().map(|c| column_kind(c)).collect();
            for (c, k) in cols.iter().zip(&kinds) {
                if k.is_none() {
                    out.push(format!("{}: {c}", p.display()));
                }
            }
            for (l, line) in lines.enumerate() {
                for ((cell, c), k) in line.split(',').zip(&cols).zip(&kinds) {
                    if *k == Some(ColumnKind::Integer) && !is_integer_cell(cell) {
                        out.push(format!("{}:{}: {c} = {cell}", p.display(), l + 2));
                        break;
                    }
                }
            }
        }
    }
    out
}

/// The columns outside the convention in the headers of the CSV files in `dir` and the
/// integer columns written otherwise ([`csv_violations`]; the name of issue 20's check).
pub fn columns_without_unit(dir: &Path) -> Vec<String> {
    csv_violations(dir)
}

/// A CSV file being written row by row (under a temporary name until finished or dropped).
pub struct CsvSink {
    path: PathBuf,
    part: PathBuf,
    writer: Option<csv::Writer<BufWriter<File>>>,
    names: Vec<String>,
    kinds: Vec<ColumnKind>,
}

impl CsvSink {
    /// Append one row (must have as many values as the header has columns). Real columns are
    /// written `{:.10e}`; integer columns ([`ColumnKind::Integer`]: names ending in
    /// [`INTEGER_MARKERS`] or in [`INTEGER_NAMES`]) as integers (`3`, `0`/`1`; `NaN` for a
    /// missing value), and a value there that is not a whole number of magnitude below 2⁵³ is
    /// an error naming the column.
    pub fn row(&mut self, values: &[f64]) -> Result<(), CliError> {
        if values.len() != self.kinds.len() {
            return Err(CliError::Write {
                path: self.path.clone(),
                message: format!(
                    "row has {} values, header has {}",
                    values.len(),
                    self.kinds.len()
                ),
            });
        }
        let mut cells = Vec::with_capacity(values.len());
        for (k, (&v, kind)) in values.iter().zip(&self.kinds).enumerate() {
            cells.push(match kind {
                ColumnKind::Real => format!("{v:.10e}"),
                ColumnKind::Integer if v.is_nan() => "NaN".to_string(),
                ColumnKind::Integer if v.fract() == 0.0 && v.abs() < 9.007_199_254_740_992e15 => {
                    format!("{}", v as i64)
                }
                ColumnKind::Integer => {
                    return Err(CliError::Write {
                        path: self.path.clone(),
                        message: format!(
                            "column {} ({}) holds integers, got {v}",
                            k + 1,
                            self.names[k]
                        ),
                    });
                }
            });
        }
        let Some(w) = self.writer.as_mut() else {
            return Err(CliError::write(&self.path, "already finished"));
        };
        w.write_record(&cells)
            .map_err(|e| CliError::write(&self.path, e))
    }

    /// Flush to disk (also done on drop, silently).
    pub fn flush(&mut self) -> Result<(), CliError> {
        match self.writer.as_mut() {
            Some(w) => w.flush().map_err(|e| CliError::write(&self.path, e)),
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
            w.flush().map_err(|e| CliError::write(&self.path, e))?;
            drop(w);
            std::fs::rename(&self.part, &self.path).map_err(|e| CliError::write(&self.path, e))?;
        }
        Ok(())
    }
}

impl Drop for CsvSink {
    fn drop(&mut self) {
        let _ = self.close();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // definition of the convention (issue 39 item 3): SI symbols in their case, `_per_` for a
    // quotient, integer markers; the spellings it replaced are refused although their last
    // part alone reads as a unit (`rad_s` ends in `_s`, `n_m` in `_m`). Reference: the table
    // in the rustdoc of `UNIT_SUFFIXES` and `LEGACY_SUFFIXES`.
    #[test]
    fn columns_follow_the_one_convention() {
        let real: &[&str] = &[
            "t_s",
            "torque_N_m",
            "delta_omega_rad_per_s",
            "fy_amp_N",
            "speed_km_per_h",
            "frequency_Hz",
            "energy_J",
            "pressure_Pa",
            "eigenvalue_rad2_per_s2",
            "growth_rate_1_per_s",
            "spindle_fx_N_per_sqrt_kg",
            "z1_sqrt_kg_m",
            "tension_N",
            "pressure_N_per_m",
            "slip_velocity_m_per_s",
            "damping_ratio",
            "green_strain",
            "s_m",
        ];
        let integer: &[&str] = &[
            "mode",
            "n",
            "pulley_index",
            "active_nodes_count",
            "gross_slip_flag",
        ];
        let refused: &[&str] = &[
            "t",
            "torque",
            "hz",
            "delta_omega",
            "tension",
            "_s",
            "x",
            "torque_Nm",
            "delta_omega_rad_s",
            "fy_amp_n",
            "speed_kmh",
            "normal_force_n_m",
            "growth_rate_1_s",
            "belt_speed_m_s",
            "f_hz",
            "energy_j",
            "pressure_pa",
            "pulley",
            "active_nodes",
        ];
        for (names, kind) in [
            (real, Some(ColumnKind::Real)),
            (integer, Some(ColumnKind::Integer)),
            (refused, None),
        ] {
            for name in names {
                assert_eq!(column_kind(name), kind, "{name}");
            }
        }
        assert!(is_integer_cell("3") && is_integer_cell("-1") && is_integer_cell("NaN"));
        assert!(!is_integer_cell("0.0000000000e0") && !is_integer_cell("1.5"));
        assert!(!is_integer_cell("") && !is_integer_cell("-"));
    }

    // integer columns are written as integers and checked; a breach of either half of the
    // convention is reported by `csv_violations` (reference: the cells written by hand below)
    #[test]
    fn integer_columns_are_written_and_checked_as_integers() {
        let dir = crate::testing::fresh_dir("flowmbd-cli", "int");
        let out = OutputDir::create(&dir).unwrap();
        let p = out
            .write_csv(
                "a.csv",
                &["pulley_index", "torque_N_m", "slip_flag", "mode"],
                [[3.0, 0.5, 1.0, f64::NAN], [0.0, -2.0, 0.0, 12.0]],
            )
            .unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[1], "3,5.0000000000e-1,1,NaN");
        assert_eq!(lines[2], "0,-2.0000000000e0,0,12");
        assert!(
            csv_violations(&dir).is_empty(),
            "{:?}",
            csv_violations(&dir)
        );
        // a fraction in an integer column is refused, naming the column
        let mut sink = out.csv("b.csv", &["node_index"]).unwrap();
        let e = sink.row(&[2.5]).unwrap_err().to_string();
        assert!(e.contains("node_index"), "{e}");
        drop(sink);
        std::fs::remove_file(dir.join("b.csv")).unwrap();
        // files written otherwise: a header outside the convention, a flag as a float
        out.write_text("c.csv", "t_s,speed_kmh\n0,1\n").unwrap();
        out.write_text("d.csv", "t_s,on_flag\n0,1\n1,0.0000000000e0\n")
            .unwrap();
        let v = csv_violations(&dir);
        assert_eq!(v.len(), 2, "{v:?}");
        assert!(v[0].ends_with("c.csv: speed_kmh"), "{v:?}");
        assert!(v[1].ends_with("d.csv:3: on_flag = 0.0000000000e0"), "{v:?}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn csv_round_trip_and_row_length_check() {
        let dir = crate::testing::fresh_dir("flowmbd-cli", "out");
        let out = OutputDir::create(&dir).unwrap();
        let p = out
            .write_csv("t.csv", &["t_s", "x_m"], [[0.0, 1.5], [0.5, -2.0]])
            .unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("t_s,x_m"));
        let second: Vec<f64> = lines
            .nth(1)
            .unwrap()
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(second, vec![0.5, -2.0]);
        let mut sink = out.csv("u.csv", &["a_m", "b_m"]).unwrap();
        assert!(sink.row(&[1.0]).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    // issue 35 item 3: the files a run wrote into a sub-folder (VTK frames) are listed one by
    // one and removed by the next run, the folder too once empty; a user's file beside them
    // and names reaching outside the folder are left alone
    #[test]
    fn files_in_sub_folders_are_listed_and_cleared() {
        let dir = crate::testing::fresh_dir("flowmbd-cli", "sub");
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
