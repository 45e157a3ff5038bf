//! Progress bars on stderr for long runs.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// A progress bar over a known amount of work (e.g. simulated seconds, sweep points).
///
/// Hidden when `quiet` is set or stderr is not a terminal, so piped output and CI logs stay clean.
pub struct Progress {
    bar: ProgressBar,
    scale: f64,
}

impl Progress {
    /// A bar for `total` units (e.g. the end time in seconds), labelled `message`.
    pub fn new(total: f64, message: &str, quiet: bool) -> Self {
        const TICKS: u64 = 1000;
        let bar = ProgressBar::new(TICKS);
        if quiet || !std::io::stderr().is_terminal() {
            bar.set_draw_target(ProgressDrawTarget::hidden());
        }
        if let Ok(style) = ProgressStyle::with_template(
            "{msg:24} [{elapsed_precise}] {wide_bar} {percent:>3}% eta {eta}",
        ) {
            bar.set_style(style);
        }
        bar.set_message(message.to_string());
        let scale = if total > 0.0 {
            TICKS as f64 / total
        } else {
            0.0
        };
        Self { bar, scale }
    }

    /// Report that `done` units of the total are complete.
    pub fn set(&self, done: f64) {
        self.bar
            .set_position((done * self.scale).clamp(0.0, 1000.0) as u64);
    }

    /// Change the label.
    pub fn message(&self, message: &str) {
        self.bar.set_message(message.to_string());
    }

    /// Remove the bar.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}
