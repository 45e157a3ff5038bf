//! Time histories of chosen quantities, written as CSV.

use crate::MbdError;
use crate::integrators::State;
use std::io::Write;
use std::path::Path;

/// A probe: a named scalar function of the state.
pub struct Probe<'a> {
    /// Column name (with unit, e.g. `"slider x \[m\]"`).
    pub name: String,
    /// The quantity.
    pub f: Box<dyn Fn(&State) -> f64 + 'a>,
}

impl<'a> Probe<'a> {
    /// New probe.
    pub fn new(name: &str, f: impl Fn(&State) -> f64 + 'a) -> Self {
        Self {
            name: name.into(),
            f: Box::new(f),
        }
    }
}

/// Recorded time history: a time column `t \[s\]` and one column per probe.
pub struct History<'a> {
    probes: Vec<Probe<'a>>,
    /// Record every `every`-th observed state (1 = all).
    pub every: usize,
    seen: usize,
    /// Times \[s\].
    pub t: Vec<f64>,
    /// Rows of probe values (same order as the probes).
    pub rows: Vec<Vec<f64>>,
}

impl<'a> History<'a> {
    /// History of the given probes, recording every observed state.
    pub fn new(probes: Vec<Probe<'a>>) -> Self {
        Self {
            probes,
            every: 1,
            seen: 0,
            t: Vec::new(),
            rows: Vec::new(),
        }
    }

    /// Records `state` (use as, or inside, an integrator observer).
    pub fn observe(&mut self, state: &State) {
        let keep = self.seen.is_multiple_of(self.every.max(1));
        self.seen += 1;
        if keep {
            self.t.push(state.t);
            self.rows
                .push(self.probes.iter().map(|p| (p.f)(state)).collect());
        }
    }

    /// Column names (without the time column).
    pub fn names(&self) -> Vec<&str> {
        self.probes.iter().map(|p| p.name.as_str()).collect()
    }

    /// Values of the column `name`.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.probes.iter().position(|p| p.name == name)?;
        Some(self.rows.iter().map(|r| r[k]).collect())
    }

    /// Writes the history as CSV (header `t \[s\]`, probe names; full precision).
    pub fn write_csv<W: Write>(&self, w: W, label: &str) -> Result<(), MbdError> {
        let io = |e: csv::Error| MbdError::Io {
            path: label.into(),
            message: e.to_string(),
        };
        let mut wr = csv::Writer::from_writer(w);
        let mut header = vec!["t [s]".to_string()];
        header.extend(self.probes.iter().map(|p| p.name.clone()));
        wr.write_record(&header).map_err(io)?;
        for (t, row) in self.t.iter().zip(&self.rows) {
            let mut rec = vec![format!("{t:e}")];
            rec.extend(row.iter().map(|x| format!("{x:e}")));
            wr.write_record(&rec).map_err(io)?;
        }
        wr.flush().map_err(|e| MbdError::Io {
            path: label.into(),
            message: e.to_string(),
        })
    }

    /// Writes the history to the CSV file `path`.
    pub fn save_csv(&self, path: &Path) -> Result<(), MbdError> {
        let f = std::fs::File::create(path).map_err(|e| MbdError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        self.write_csv(std::io::BufWriter::new(f), &path.display().to_string())
    }
}
