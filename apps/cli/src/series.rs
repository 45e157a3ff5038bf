//! A VTK time series in a study's output folder, the one output observer of every study that
//! writes frames (belt ANCF/plate/wave, tire cleat): the frames `vtk/<stem>_NNNN.<ext>` and
//! the ParaView index `<stem>.<ext>.series` (JSON, `{"file-series-version": "1.0", "files":
//! [{"name", "time"}]}`) listing each frame with its simulated time \[s\].

use crate::error::CliError;
use crate::output::OutputDir;
use std::path::PathBuf;

/// A VTK time series (module documentation).
#[derive(Debug, Clone)]
pub struct VtkSeries {
    stem: String,
    ext: &'static str,
    /// Interval between frames \[s\] for [`Self::due`] (≤ 0: none are due).
    interval: f64,
    /// Simulated time of the next frame due (`None` before the first).
    next: Option<f64>,
    /// The frames so far: name relative to the folder and simulated time \[s\].
    files: Vec<(String, f64)>,
}

impl VtkSeries {
    /// A series of frames `vtk/<stem>_NNNN.<ext>` in `out`, one due every `interval` \[s\] of
    /// simulated time ([`Self::due`]; ≤ 0: none due). The folder `vtk` is created when the
    /// first frame is named.
    pub fn new(stem: &str, ext: &'static str, interval: f64) -> Self {
        Self {
            stem: stem.to_string(),
            ext,
            interval,
            next: None,
            files: Vec::new(),
        }
    }

    /// The path of the next frame, at simulated time `t` \[s\], recorded in the index.
    pub fn frame(&mut self, out: &OutputDir, t: f64) -> Result<PathBuf, CliError> {
        let dir = out.path("vtk");
        if self.files.is_empty() {
            std::fs::create_dir_all(&dir).map_err(|e| CliError::write(&dir, e))?;
        }
        let name = format!("vtk/{}_{:04}.{}", self.stem, self.files.len(), self.ext);
        let path = out.path(&name);
        self.files.push((name, t));
        Ok(path)
    }

    /// [`Self::frame`] if a frame is due at simulated time `t` \[s\]: the first call's, then
    /// one an interval on (a frame per call at most: intervals shorter than the caller's steps
    /// are skipped).
    pub fn due(&mut self, out: &OutputDir, t: f64) -> Result<Option<PathBuf>, CliError> {
        if self.interval <= 0.0 || self.next.is_some_and(|n| t < n) {
            return Ok(None);
        }
        let mut next = self.next.unwrap_or(t);
        while next <= t {
            next += self.interval;
        }
        self.next = Some(next);
        self.frame(out, t).map(Some)
    }

    /// Number of frames so far.
    pub fn len(&self) -> usize {
        self.files.len()
    }

    /// Whether no frame was named yet.
    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// Write the index `<stem>.<ext>.series` of the frames so far (none: nothing written).
    pub fn finish(&self, out: &OutputDir) -> Result<Option<PathBuf>, CliError> {
        if self.files.is_empty() {
            return Ok(None);
        }
        let files: Vec<_> = self
            .files
            .iter()
            .map(|(n, t)| serde_json::json!({"name": n, "time": t}))
            .collect();
        let index = serde_json::json!({"file-series-version": "1.0", "files": files});
        out.write_json(&format!("{}.{}.series", self.stem, self.ext), &index)
            .map(Some)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Definition of the schedule: the first call is due, then one frame per interval of
    // simulated time; the frames are numbered in order and the index lists them with their
    // times (ParaView's `.series` format).
    #[test]
    fn frames_every_interval_and_the_index_lists_them() {
        let root = crate::testing::fresh_dir("flowmbd-cli", "series");
        let out = OutputDir::create(&root).unwrap();
        // steps of 0.25 s, frames every 0.75 s (exact binary fractions)
        let mut s = VtkSeries::new("belt", "vtk", 0.75);
        let mut due = Vec::new();
        for k in 0..=10 {
            let t = 0.25 * k as f64;
            if let Some(p) = s.due(&out, t).unwrap() {
                std::fs::write(&p, "x").unwrap();
                due.push(t);
            }
        }
        assert_eq!(due, vec![0.0, 0.75, 1.5, 2.25]);
        assert!(root.join("vtk/belt_0003.vtk").exists());
        let index: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(root.join("belt.vtk.series")).unwrap_or_default(),
        )
        .unwrap_or_default();
        assert!(index.is_null(), "no index before finish");
        s.finish(&out).unwrap();
        let index: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(root.join("belt.vtk.series")).unwrap())
                .unwrap();
        assert_eq!(index["files"].as_array().unwrap().len(), 4);
        assert_eq!(index["files"][1]["name"], "vtk/belt_0001.vtk");
        assert_eq!(index["files"][1]["time"], 0.75);
        let none = VtkSeries::new("tire", "vtu", 0.0);
        assert!(none.finish(&out).unwrap().is_none());
        let _ = std::fs::remove_dir_all(&root);
    }
}
