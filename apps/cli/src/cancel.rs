//! Cancellation of a running study by SIGINT (Ctrl-C) or SIGTERM (issue 35, item 3).
//!
//! [`run_study`](crate::run_study) installs the handler ([`Cancel::install`]) before a study
//! runs and hands the token to the study as [`StudyContext::cancel`](crate::StudyContext).
//! The handler only records which signal arrived (signal-hook's `flag` actions: an atomic
//! store, async-signal-safe); nothing is stopped asynchronously. The study's library loops
//! poll the token through the callbacks they already take: a progress or observer closure
//! returns [`Cancel::check`] (`ControlFlow::Break(())` once a signal arrived), the loop stops
//! after the current step and returns what it has computed (see
//! [`mbd_core::integrators::Proceed`]). The runner then writes the results so far into
//! `summary.json` with `"complete": false, "status": "interrupted"` and exits with 130
//! (SIGINT) or 143 (SIGTERM) after one line on stderr. A second signal while the run winds
//! down ends the process at once with the same code.
//!
//! The token is plain data passed down (no global state in the libraries); only the
//! handler's registration is process-wide, and it lives here in the app layer.

use std::ops::ControlFlow;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// SIGINT's number (Ctrl-C); exit code 128 + 2 = 130.
pub const SIGINT: usize = 2;
/// SIGTERM's number; exit code 128 + 15 = 143.
pub const SIGTERM: usize = 15;

/// A cancellation token: which termination signal arrived, if any (cheap to clone, shared).
#[derive(Debug, Clone, Default)]
pub struct Cancel {
    signal: Arc<AtomicUsize>,
    armed: Arc<AtomicBool>,
}

impl Cancel {
    /// A token no signal sets (library callers, tests); [`request`](Self::request) sets it.
    pub fn new() -> Self {
        Self::default()
    }

    /// A token set by SIGINT and SIGTERM: the first signal records its number; a second one
    /// exits the process at once with 128 + its number. Falls back to an unset token when the
    /// handler cannot be installed (the run then ends as before on a signal).
    pub fn install() -> Self {
        let c = Self::new();
        #[cfg(unix)]
        {
            use signal_hook::flag;
            for sig in [SIGINT, SIGTERM] {
                let s = sig as std::ffi::c_int;
                // order matters: the shutdown action runs first and fires only once armed
                let _ = flag::register_conditional_shutdown(s, 128 + s, Arc::clone(&c.armed));
                let _ = flag::register_usize(s, Arc::clone(&c.signal), sig);
                let _ = flag::register(s, Arc::clone(&c.armed));
            }
        }
        c
    }

    /// Record `signal` as if it had arrived (tests, or a caller cancelling from code).
    pub fn request(&self, signal: usize) {
        self.signal.store(signal, Ordering::SeqCst);
        self.armed.store(true, Ordering::SeqCst);
    }

    /// The signal that arrived, if any ([`SIGINT`] or [`SIGTERM`]).
    pub fn signal(&self) -> Option<usize> {
        match self.signal.load(Ordering::SeqCst) {
            0 => None,
            s => Some(s),
        }
    }

    /// Whether the run was asked to stop.
    pub fn is_cancelled(&self) -> bool {
        self.signal().is_some()
    }

    /// The answer for a library loop's progress or observer callback: `Continue`, or
    /// `Break(())` once a signal arrived.
    pub fn check(&self) -> ControlFlow<()> {
        if self.is_cancelled() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }

    /// The signal's name for messages (`SIGINT`, `SIGTERM`, or `signal N`).
    pub fn signal_name(&self) -> String {
        match self.signal() {
            Some(SIGINT) => "SIGINT".into(),
            Some(SIGTERM) => "SIGTERM".into(),
            Some(s) => format!("signal {s}"),
            None => "no signal".into(),
        }
    }

    /// The process exit code after the signal: 128 + its number (130, 143).
    pub fn exit_code(&self) -> u8 {
        (128 + self.signal().unwrap_or(0)).min(255) as u8
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // definition: the shell's convention 128 + signal number
    #[test]
    fn a_requested_signal_breaks_the_loop_and_names_the_exit_code() {
        let c = Cancel::new();
        assert!(c.check().is_continue());
        assert_eq!(c.signal(), None);
        let shared = c.clone();
        shared.request(SIGTERM);
        assert!(c.check().is_break());
        assert_eq!(c.exit_code(), 143);
        assert_eq!(c.signal_name(), "SIGTERM");
        let d = Cancel::new();
        d.request(SIGINT);
        assert_eq!(d.exit_code(), 130);
    }
}
